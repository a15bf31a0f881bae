#include "app/render/image.h"

#include <cstring>
#include <stdexcept>

#include "engine/util/files.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb_image_write.h>

namespace prep::render {

Image image_from_bottom_up(const std::uint8_t* rgba, int width, int height) {
  Image image(width, height);
  const size_t row = static_cast<size_t>(width) * 4;
  for (int y = 0; y < height; ++y) std::memcpy(&image.rgba[y * row], rgba + (height - 1 - y) * row, row);
  return image;
}

std::string encode_png(const Image& image) {
  if (image.width <= 0 || image.height <= 0) throw std::runtime_error("encode_png: empty image");
  std::string bytes;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &bytes, image.width, image.height, 4, image.rgba.data(), image.width * 4))
    throw std::runtime_error("encode_png: stb_image_write failed");
  return bytes;
}

void write_png(const Image& image, const std::string& path) { write_file_atomic(path, encode_png(image)); }

}  // namespace prep::render
