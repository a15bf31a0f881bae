#include "app/demo/motion_folder.h"

#include <filesystem>

#include "engine/util/files.h"
#include "engine/world/set_course.h"
#include "engine/world/world.h"

namespace prep::demo {

std::shared_ptr<const MotionFolder> open_motion_folder(const std::string& folder, const std::string& course,
                                                       const std::string& cache_dir) {
  auto out = std::make_shared<MotionFolder>();
  const Params params;
  out->scan = scan_motion_folder(folder, params);
  const std::filesystem::path where = std::filesystem::absolute(std::filesystem::path(cache_dir) / "sets" / out->scan.name);
  std::filesystem::create_directories(where);
  out->manifest = (where / (out->scan.name + ".json")).string();
  write_file_atomic(out->manifest, scan_manifest_json(out->scan, out->manifest).dump(2) + "\n");

  const Scenario original = load_scenario(course);
  const WorldAssets assets = make_world_assets(std::make_shared<const MotionSet>(load_motion_set(out->manifest, params)), params);
  SetCourse fitted = course_for_set(original, assets, out->manifest);
  fitted.scenario.name = original.name + " on " + out->scan.name;
  fitted.scenario.params_file.clear();  // a course's Params may name clips of another set: the defaults
  out->scenario = (where / ("course-" + out->scan.name + ".json")).string();
  write_file_atomic(out->scenario, scenario_json(fitted.scenario) + "\n");
  out->changes = std::move(fitted.changes);
  return out;
}

}  // namespace prep::demo
