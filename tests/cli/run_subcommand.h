// Runs a registered `prep` subcommand in-process, as `prep NAME ARGS...`, and returns what it printed.
#pragma once

#include <algorithm>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli/command.h"

namespace prep::test {

inline std::string run_subcommand(const std::string& name, std::vector<std::string> args) {
  CLI::App app{"test"};
  for (auto& c : cli::commands())
    if (c.name == name) c.define(*app.add_subcommand(c.name, c.help));
  args.insert(args.begin(), name);
  std::reverse(args.begin(), args.end());  // CLI11 takes a vector in reverse order
  std::ostringstream captured;
  auto* previous = std::cout.rdbuf(captured.rdbuf());
  try {
    app.parse(args);
  } catch (...) {
    std::cout.rdbuf(previous);
    throw;
  }
  std::cout.rdbuf(previous);
  return captured.str();
}

}  // namespace prep::test
