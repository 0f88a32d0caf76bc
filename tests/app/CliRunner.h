#pragma once
// Runs the `mfadvr` program under test and captures its exit status and output.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace mfadvr::test {

struct CliResult {
  int status = -1;
  std::string out, err;
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// `args` is appended to the program path as a shell command line; `env` (e.g. "NAME=value")
// goes before it.
inline CliResult runMfadvr(const std::string& args, const std::string& env = "") {
  const auto dir = std::filesystem::path(MFADVR_TEST_TMP_DIR) / "cli-output";
  std::filesystem::create_directories(dir);
  const auto outFile = dir / (std::to_string(::getpid()) + ".stdout");
  const auto errFile = dir / (std::to_string(::getpid()) + ".stderr");
  const std::string cmd = (env.empty() ? "" : env + " ") + std::string(MFADVR_EXE) + " " + args +
                          " >" + outFile.string() + " 2>" + errFile.string();
  const int raw = std::system(cmd.c_str());
  CliResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(outFile);
  r.err = slurp(errFile);
  return r;
}

}  // namespace mfadvr::test
