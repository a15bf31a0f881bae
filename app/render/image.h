// An RGBA8 image, top row first, written as PNG (stb_image_write, atomically) and read back (stb_image).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace prep::render {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4 bytes, row 0 is the top of the picture

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgba(static_cast<size_t>(w) * h * 4, 0) {}
  const std::uint8_t* pixel(int x, int y) const { return &rgba[(static_cast<size_t>(y) * width + x) * 4]; }
  std::uint8_t* pixel(int x, int y) { return &rgba[(static_cast<size_t>(y) * width + x) * 4]; }
};

// Copies a bottom-up buffer (OpenGL's row order) into a top-down Image.
Image image_from_bottom_up(const std::uint8_t* rgba, int width, int height);

// PNG bytes of the image (stbi_write_png_to_func into memory).
std::string encode_png(const Image& image);

// Encodes and writes through prep::write_file_atomic. Throws std::runtime_error naming the file on failure.
void write_png(const Image& image, const std::string& path);

// Reads a PNG as RGBA. Throws InputError naming the file when it cannot be read or is not a PNG.
Image read_png(const std::string& path);

}  // namespace prep::render
