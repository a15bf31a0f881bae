// BVH import and export.
#pragma once

#include <string>
#include <vector>

#include "engine/motion/clip.h"

namespace prep {

struct BvhReadOptions {
  float unit_scale = 0.01f;  // file units -> metres (centimetres by default; 0.0254 inches, 0.05644 CMU units)
  std::vector<std::string>* warnings = nullptr;  // e.g. a declared frame count that differs from the data
};

// Reads a BVH file: any rotation order per joint, 3- and 6-channel joints mixed, End Sites, CRLF and tabs,
// exponent notation, locale-independent numbers. Rotations become quaternions (hemisphere-continuous).
// Throws InputError naming the file and line for anything malformed.
Clip read_bvh(const std::string& path, const BvhReadOptions& options = {});
Clip parse_bvh(const std::string& text, const std::string& source_name, const BvhReadOptions& options = {});

struct BvhWriteOptions {
  float unit_scale = 0.01f;  // metres -> file units are divided by this (centimetres by default)
};

// Writes a BVH that Blender's importer reads: root with 6 channels (Xposition Yposition Zposition Zrotation
// Xrotation Yrotation), other joints 3 channels ZXY, degrees. Written atomically.
void write_bvh(const Clip& clip, const std::string& path, const BvhWriteOptions& options = {});
std::string format_bvh(const Clip& clip, const BvhWriteOptions& options = {});

}  // namespace prep
