// Errors that name where they come from: a file and, when known, a line or a field.
#pragma once

#include <stdexcept>
#include <string>

namespace prep {

// Thrown for bad input (a malformed BVH, glTF, manifest, scenario, policy or params file).
// what() reads "FILE:LINE: message" or "FILE: message" so that a user can go straight to the spot.
// Control characters in the message (quoted from the file: a field name, a token) and in the file's name are
// shown as \xNN: a NUL would otherwise end what() there, and an escape sequence would garble a terminal.
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, int line, const std::string& message)
      : std::runtime_error(format(file, line, message)), file_(file), line_(line) {}
  InputError(const std::string& file, const std::string& message) : InputError(file, 0, message) {}

  const std::string& file() const { return file_; }
  int line() const { return line_; }

  // Text as what() shows it: newlines and tabs stay (some messages span lines); other control characters
  // become \xNN. The file's name is shown so too (a path may hold anything but a NUL, and a name read from
  // a file may hold even that).
  static std::string printable(const std::string& text) {
    static const char* const kHex = "0123456789abcdef";
    std::string out;
    out.reserve(text.size());
    for (const char ch : text) {
      const auto c = static_cast<unsigned char>(ch);
      if ((c < 0x20 && c != '\n' && c != '\t') || c == 0x7f) {
        out += "\\x";
        out += kHex[c >> 4];
        out += kHex[c & 15];
      } else {
        out += ch;
      }
    }
    return out;
  }

 private:
  static std::string format(const std::string& file, int line, const std::string& message) {
    return line > 0 ? printable(file) + ":" + std::to_string(line) + ": " + printable(message)
                    : printable(file) + ": " + printable(message);
  }
  std::string file_;
  int line_;
};

}  // namespace prep
