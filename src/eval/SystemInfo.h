#pragma once
// What the report records about where it ran: the machine, the operating system and the
// versions of the software that took part.
#include <string>
#include <vector>

namespace mfadvr::eval {

// "label: value" lines: CPU, cores, memory, OS, compiler, mfadvr, VTK, Eigen, TBB.
std::vector<std::pair<std::string, std::string>> systemDescription();

}  // namespace mfadvr::eval
