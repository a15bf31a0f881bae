#include "app/render/image.h"

#include <cstring>
#include <stdexcept>

#include "engine/util/error.h"
#include "engine/util/files.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb_image_write.h>
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#include <stb_image.h>

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

Image read_png(const std::string& path) {
  const std::string bytes = read_file(path);  // InputError naming the file when it cannot be read
  int w = 0, h = 0, channels = 0;
  stbi_uc* pixels = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), static_cast<int>(bytes.size()),
                                          &w, &h, &channels, 4);
  if (!pixels) throw InputError(path, std::string("not a PNG image (") + stbi_failure_reason() + ")");
  Image image(w, h);
  std::memcpy(image.rgba.data(), pixels, image.rgba.size());
  stbi_image_free(pixels);
  return image;
}

}  // namespace prep::render
