// prep: the command-line tool over the engine (no window, no GL).
#include <algorithm>
#include <exception>
#include <iostream>
#include <tuple>

#include "app/cli/command.h"

namespace prep::cli {
std::vector<Command>& commands() {
  static std::vector<Command> all;
  return all;
}
}  // namespace prep::cli

int main(int argc, char** argv) {
  CLI::App app{"prep: natural preparation behaviour synthesis (Shum et al. 2013).\n"
               "Loads motion, synthesizes prepared movement, trains and evaluates controllers."};
  app.require_subcommand(1);
  auto& cmds = prep::cli::commands();
  // By order, then name: the registration order depends on how the files were linked.
  std::sort(cmds.begin(), cmds.end(), [](const auto& a, const auto& b) { return std::tie(a.order, a.name) < std::tie(b.order, b.name); });
  for (auto& c : cmds) c.define(*app.add_subcommand(c.name, c.help));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "prep: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
