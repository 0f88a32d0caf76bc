#pragma once
// One exception type for every user-facing failure (bad input, bad file, bad options).
// The command line turns it into a message on stderr and exit status 1.
#include <stdexcept>
#include <string>

namespace mfadvr {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace mfadvr
