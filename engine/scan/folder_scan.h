// A folder of BVH takes turned into a motion-set manifest: units, the reference skeleton, each take's
// clips with their roles, loop ranges and T_t, steered turns and the slow walk, and what the set lacks.
// Every guess carries its evidence and a confidence; the manifest written from it can be edited by hand.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/motion/motion_set.h"
#include "engine/params/params.h"
#include "engine/scan/loop_search.h"

namespace prep {

struct ScannedClip {
  std::string name;
  std::string file;
  Role role = Role::Walk;
  int first = 0;                     // frame range in the file's frames (inclusive)
  int last = 0;
  std::optional<LoopRange> loop;     // cyclic locomotion
  std::optional<int> target_frame;   // T_t (target motions)
  float steer_deg_per_s = 0.0f;      // a turn steered from a walk; 0 for a take as recorded
  float speed = 0.0f;                // ground speed over the loop (or the clip), m/s
  float role_confidence = 0.0f;
  float timing_confidence = 0.0f;    // of T_t, or of the loop (LoopRange::confidence)
  std::string evidence;              // why this role; what T_t or the loop was found from
  bool core = false;                 // one of the controller's core motions (default_core_clips)
  std::string core_as;               // "walk", "turn left", "turn right", "slow walk"
};

struct ScannedFile {
  std::string file;
  int frames = 0;
  float fps = 0.0f;
  int joints = 0;
  int first_usable = 0;    // after a reference pose and the blend out of it
  bool used = false;
  std::string note;        // why a file was left out, or a non-fatal finding
};

struct FolderScan {
  std::string folder;      // as given
  std::string name;        // the folder's name
  std::string units;       // a unit name load_motion_set knows ("centimetres", "cmu", ...)
  float unit_scale = 0.01f;
  float figure_height = 0.0f;  // m, the reference skeleton's rest pose from toe to head
  bool skip_first_frame = false;
  std::string reference;   // the file whose skeleton the set plays on
  std::vector<ScannedFile> files;
  std::vector<ScannedClip> clips;
  std::vector<std::string> lacks;  // what a scenario cannot do with this set, and what stands in
};

// Scans every *.bvh file in `folder` (not its subfolders). Throws InputError naming the folder when it
// holds no BVH or no file with a recognisable humanoid, and naming the file (and line) for a malformed one.
FolderScan scan_motion_folder(const std::string& folder, const Params& params);

// The manifest (motion_set.h's schema) for a scan, its "folder" relative to where it will be written
// (`manifest_path`), or absolute when the two share no root.
nlohmann::json scan_manifest_json(const FolderScan& scan, const std::string& manifest_path);

// What the scan found, for `prep manifest --json`.
nlohmann::json scan_report_json(const FolderScan& scan);

// The same as a table for a terminal.
std::string scan_report_text(const FolderScan& scan);

}  // namespace prep
