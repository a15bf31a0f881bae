#include <doctest/doctest.h>

#include <string>

#include "engine/util/error.h"

using namespace prep;

TEST_CASE("an InputError names the file and the line, and shows control characters from the file as \\xNN") {
  CHECK(std::string(InputError("a.bvh", 12, "bad token").what()) == "a.bvh:12: bad token");
  CHECK(std::string(InputError("a.json", "bad field").what()) == "a.json: bad field");
  // A NUL quoted from the file (a JSON key "\u0000clips") used to end what() right after "a.json: ".
  const InputError nul("a.json", std::string("'\0clips' is not a known field", 29));
  CHECK(std::string(nul.what()) == "a.json: '\\x00clips' is not a known field");
  CHECK(std::string(InputError("a.json", "escape \x1b[2J, delete \x7f").what()) == "a.json: escape \\x1b[2J, delete \\x7f");
  // So does the file's name, read from another file (a manifest's "file": "walk\u0000.bvh"), while file()
  // keeps the name as it was given.
  const InputError named(std::string("walk\0.bvh", 9), "cannot open the file");
  CHECK(std::string(named.what()) == "walk\\x00.bvh: cannot open the file");
  CHECK(named.file() == std::string("walk\0.bvh", 9));
  CHECK(InputError::printable(named.file()) == "walk\\x00.bvh");
  // Newlines and tabs stay: some messages span lines.
  CHECK(std::string(InputError("a.gltf", "first\n\tsecond").what()) == "a.gltf: first\n\tsecond");
}
