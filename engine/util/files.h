// Reading and atomically writing whole files.
#pragma once

#include <string>
#include <string_view>

namespace prep {

// Reads a whole file; throws InputError naming the file when it cannot be opened or read.
std::string read_file(const std::string& path);

// Writes `bytes` to `path` atomically: a temporary file in the same folder, flushed, then renamed over
// the target, so a reader never sees a half-written file and a failed write loses nothing.
// Throws std::runtime_error naming the file on failure.
void write_file_atomic(const std::string& path, std::string_view bytes);

// The repository root (compiled in), used to find assets/ and ../shared/ by default.
std::string source_dir();

}  // namespace prep
