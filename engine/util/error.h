// Errors that name where they come from: a file and, when known, a line or a field.
#pragma once

#include <stdexcept>
#include <string>

namespace prep {

// Thrown for bad input (a malformed BVH, glTF, manifest, scenario, policy or params file).
// what() reads "FILE:LINE: message" or "FILE: message" so that a user can go straight to the spot.
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, int line, const std::string& message)
      : std::runtime_error(format(file, line, message)), file_(file), line_(line) {}
  InputError(const std::string& file, const std::string& message) : InputError(file, 0, message) {}

  const std::string& file() const { return file_; }
  int line() const { return line_; }

 private:
  static std::string format(const std::string& file, int line, const std::string& message) {
    return line > 0 ? file + ":" + std::to_string(line) + ": " + message : file + ": " + message;
  }
  std::string file_;
  int line_;
};

}  // namespace prep
