// prep info: a description of a motion set, as text or JSON. Other parts of prep add sections (e.g. the
// motion graph, the targets) with one RegisterInfoSection in their own file; info.cpp needs no edit.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "engine/motion/motion_set.h"
#include "engine/params/params.h"

namespace prep::cli {

struct InfoSection {
  std::string key;  // the section's field in the JSON object
  int order;        // sections appear in this order after "skeleton" and "clips"
  std::function<nlohmann::json(const MotionSet&, const Params&)> build;
  std::function<void(std::ostream&, const nlohmann::json&)> print;  // text form; null: the JSON, indented
};

std::vector<InfoSection>& info_sections();

struct RegisterInfoSection {
  explicit RegisterInfoSection(InfoSection section) { info_sections().push_back(std::move(section)); }
};

// Per-clip statistics of `prep info`.
struct ClipInfo {
  int frames = 0;
  float fps = 0;
  float seconds = 0;
  float contact_left = 0;    // fraction of frames with the left foot (heel or toe) in contact
  float contact_right = 0;
  int support_frames = 0;    // frames with at least one foot in contact
  float com_in_support = 0;  // fraction of support_frames whose COM projects inside the support polygon
};
ClipInfo clip_info(const MotionSet& set, const MotionClip& clip, const Params& params);

// The whole description: {"skeleton": {"joints": N}, "clips": [...], then every registered section}.
nlohmann::json describe_motion_set(const MotionSet& set, const Params& params);

// The same, as text for a terminal.
void print_motion_set(std::ostream& out, const MotionSet& set, const nlohmann::json& description);

}  // namespace prep::cli
