#pragma once
// The subcommands of the `mfadvr` program. Each registers its options on the CLI11 app and
// returns the function that runs it; main() maps failures to exit codes (usage 2, failure 1).
#include <CLI/CLI.hpp>
#include <functional>

namespace mfadvr::app {

struct Command {
  CLI::App* subcommand;
  std::function<int()> run;  // called after a successful parse when the subcommand was given
};

Command addEncodeCommand(CLI::App& app);
Command addInfoCommand(CLI::App& app);
Command addQueryCommand(CLI::App& app);
Command addRenderCommand(CLI::App& app);
Command addDemoCommand(CLI::App& app);
Command addCompareCommand(CLI::App& app);
Command addViewCommand(CLI::App& app);
Command addEvalCommand(CLI::App& app);
Command addDecodeCommand(CLI::App& app);

}  // namespace mfadvr::app
