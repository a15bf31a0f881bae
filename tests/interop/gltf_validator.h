// Runs the Khronos glTF-Validator (tools/gltf-validator/validate.js under Node.js) on a file.
// A missing Node.js or validator is a test failure with a clear message, never a silent pass.
#pragma once

#include <doctest/doctest.h>

#include <array>
#include <cstdio>
#include <string>
#include <sys/wait.h>

#include "tests/support/paths.h"

namespace prep::test {

struct ValidatorRun {
  int exit_code = -1;
  std::string output;
};

inline ValidatorRun run_command(const std::string& command) {
  ValidatorRun run;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return run;
  std::array<char, 4096> buf{};
  size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) run.output.append(buf.data(), n);
  const int status = ::pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

// Fails the current test unless the file has 0 errors and 0 warnings.
inline void check_gltf_valid(const std::string& path) {
  const ValidatorRun node = run_command("node --version");
  if (node.exit_code != 0)
    FAIL("Node.js is not installed, so the glTF validator cannot run (install nodejs and npm, then run "
         "scripts/setup.sh): " << node.output);
  const ValidatorRun run = run_command("node '" + repo() + "/tools/gltf-validator/validate.js' '" + path + "'");
  INFO("glTF-Validator output:\n" << run.output);
  REQUIRE_MESSAGE(run.exit_code != 2, "the validator could not run (scripts/setup.sh installs it with npm ci)");
  CHECK(run.exit_code == 0);
  CHECK(run.output.find(" 0 errors, 0 warnings") != std::string::npos);
}

}  // namespace prep::test
