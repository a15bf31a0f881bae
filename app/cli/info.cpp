// prep info: what a motion set holds.
#include <iostream>

#include "app/cli/command.h"
#include "engine/params/params.h"

namespace {
prep::cli::RegisterCommand info_command("info", "Describe a motion set: skeleton, clips, contacts, balance", 10,
                                         [](CLI::App& app) {
                                           app.callback([] { std::cout << "prep info\n"; });
                                         });
}
