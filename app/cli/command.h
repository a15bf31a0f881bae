// The `prep` tool's subcommands. Each lives in its own file and registers itself here, so adding a
// command touches no other file.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace prep::cli {

struct Command {
  std::string name;
  std::string help;
  int order;                               // position in `prep --help`
  std::function<void(CLI::App&)> define;   // adds options and a callback to the subcommand
};

std::vector<Command>& commands();

struct RegisterCommand {
  RegisterCommand(std::string name, std::string help, int order, std::function<void(CLI::App&)> define) {
    commands().push_back({std::move(name), std::move(help), order, std::move(define)});
  }
};

}  // namespace prep::cli
