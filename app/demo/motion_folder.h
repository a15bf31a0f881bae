// A folder of the user's own BVH takes, opened by the demo: scanned into a manifest (prep manifest's scan),
// and the obstacle course made playable by what the set can do. Both files go to the policy cache folder,
// beside the policies trained for the set, so the user's folder is never written to.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/scan/folder_scan.h"

namespace prep::demo {

struct MotionFolder {
  FolderScan scan;
  std::string manifest;              // the manifest written for it
  std::string scenario;              // the course written for it
  std::vector<std::string> changes;  // what the course lost or gained for this set (set_course.h)
};

// Scans `folder`, writes its manifest and `course` (a scenario file) fitted to the set under
// <cache_dir>/sets/<folder name>/. Throws InputError naming the folder or a file.
std::shared_ptr<const MotionFolder> open_motion_folder(const std::string& folder, const std::string& course,
                                                       const std::string& cache_dir);

}  // namespace prep::demo
