// What a folder scan found: as a manifest, as JSON for tools, and as a table for a terminal.
#include <cstdio>
#include <filesystem>

#include "engine/scan/folder_scan.h"

namespace prep {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

double rounded(double v, double step) { return std::round(v / step) * step; }

std::string notes_of(const ScannedClip& c) {
  char text[96];
  std::snprintf(text, sizeof text, " (role confidence %.2f%s%.2f)", c.role_confidence,
                c.loop ? ", loop confidence " : c.target_frame ? ", T_t confidence " : "", c.loop || c.target_frame ? c.timing_confidence : 0.0);
  std::string out = c.evidence + (c.loop || c.target_frame ? text : "");
  if (c.core) out += "; the controller's " + c.core_as;
  return out;
}

json clip_json(const ScannedClip& c) {
  json j;
  j["name"] = c.name;
  j["file"] = c.file;
  j["role"] = role_name(c.role);
  j["frames"] = {c.first, c.last};
  if (c.loop) j["loop"] = {c.loop->first, c.loop->last};
  if (c.target_frame) j["t_t"] = *c.target_frame;
  if (c.steer_deg_per_s != 0.0f) j["steer_deg_per_s"] = c.steer_deg_per_s;
  return j;
}

}  // namespace

json scan_manifest_json(const FolderScan& scan, const std::string& manifest_path) {
  json m;
  m["name"] = scan.name;
  m["description"] = "Written by prep manifest from the takes in " + scan.folder +
                     ". Every role, loop and T_t is a guess with its evidence in the clip's notes: edit any of them.";
  const fs::path folder = fs::absolute(scan.folder).lexically_normal();
  const fs::path beside = fs::absolute(manifest_path).parent_path().lexically_normal();
  const fs::path relative = folder.lexically_relative(beside);
  m["folder"] = relative.empty() ? folder.string() : relative.string();
  m["units"] = scan.units;
  m["skip_first_frame"] = scan.skip_first_frame;
  m["reference"] = scan.reference;
  m["floor"] = "auto";
  json clips = json::array();
  for (const ScannedClip& c : scan.clips) {
    json j = clip_json(c);
    j["notes"] = notes_of(c);
    clips.push_back(j);
  }
  m["clips"] = clips;
  return m;
}

json scan_report_json(const FolderScan& scan) {
  json r;
  r["folder"] = scan.folder;
  r["name"] = scan.name;
  r["units"] = scan.units;
  r["unit_scale"] = scan.unit_scale;
  r["figure_height_m"] = rounded(scan.figure_height, 0.001);
  r["skip_first_frame"] = scan.skip_first_frame;
  r["reference"] = scan.reference;
  json files = json::array();
  for (const ScannedFile& f : scan.files)
    files.push_back({{"file", f.file}, {"frames", f.frames}, {"fps", f.fps}, {"joints", f.joints}, {"first_usable", f.first_usable},
                     {"used", f.used}, {"note", f.note}});
  r["files"] = files;
  json clips = json::array();
  for (const ScannedClip& c : scan.clips) {
    json j = clip_json(c);
    j["role_confidence"] = rounded(c.role_confidence, 0.01);
    if (c.loop) {
      j["loop_error_cm"] = rounded(c.loop->error_cm, 0.01);
      j["loop_confidence"] = rounded(c.timing_confidence, 0.01);
    }
    if (c.target_frame) j["t_t_confidence"] = rounded(c.timing_confidence, 0.01);
    j["speed_mps"] = rounded(c.speed, 0.01);
    j["core"] = c.core ? json(c.core_as) : json(nullptr);
    j["evidence"] = c.evidence;
    clips.push_back(j);
  }
  r["clips"] = clips;
  r["lacks"] = scan.lacks;
  return r;
}

std::string scan_report_text(const FolderScan& scan) {
  std::string out;
  char line[512];
  std::snprintf(line, sizeof line, "%s: %zu BVH files, units %s (a figure %.2f m tall), reference skeleton %s%s\n\n",
                scan.folder.c_str(), scan.files.size(), scan.units.c_str(), scan.figure_height, scan.reference.c_str(),
                scan.skip_first_frame ? ", frame 0 is a reference pose" : "");
  out += line;
  std::snprintf(line, sizeof line, "%-22s %-12s %-11s %5s  %-14s %6s  %-6s %5s  %s\n", "clip", "role", "frames", "conf", "loop / T_t",
                "error", "conf", "m/s", "core");
  out += line;
  for (const ScannedClip& c : scan.clips) {
    char frames[32], timing[32] = "", error[16] = "", timing_conf[16] = "";
    std::snprintf(frames, sizeof frames, "%d-%d", c.first, c.last);
    if (c.loop) {
      std::snprintf(timing, sizeof timing, "loop %d-%d", c.loop->first, c.loop->last);
      std::snprintf(error, sizeof error, "%.1fcm", c.loop->error_cm);
      std::snprintf(timing_conf, sizeof timing_conf, "%.2f", c.timing_confidence);
    } else if (c.target_frame) {
      std::snprintf(timing, sizeof timing, "T_t %d", *c.target_frame);
      std::snprintf(timing_conf, sizeof timing_conf, "%.2f", c.timing_confidence);
    }
    if (c.steer_deg_per_s != 0.0f) std::snprintf(timing, sizeof timing, "steered %+.0f/s", c.steer_deg_per_s);
    char speed[16] = "";
    if (is_locomotion(c.role)) std::snprintf(speed, sizeof speed, "%.2f", c.speed);
    std::snprintf(line, sizeof line, "%-22s %-12s %-11s %5.2f  %-14s %6s  %-6s %5s  %s\n", c.name.c_str(), role_name(c.role), frames,
                  c.role_confidence, timing, error, timing_conf, speed, c.core_as.c_str());
    out += line;
  }
  bool any_note = false;
  for (const ScannedFile& f : scan.files)
    if (!f.note.empty()) {
      if (!any_note) out += "\nfiles:\n";
      any_note = true;
      out += "  " + f.file + ": " + f.note + "\n";
    }
  if (!scan.lacks.empty()) {
    out += "\nwhat this set lacks:\n";
    for (const std::string& l : scan.lacks) out += "  " + l + "\n";
  }
  return out;
}

}  // namespace prep
