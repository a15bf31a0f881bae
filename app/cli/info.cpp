// prep info: what a motion set holds: the skeleton, each clip with its role, length, foot contacts and
// balance (centre of mass over the support polygon), then any sections other parts of prep register.
#include "app/cli/info.h"

#include <algorithm>
#include <cstdio>
#include <iostream>

#include "app/cli/command.h"
#include "engine/library/builtin.h"
#include "engine/motion/center_of_mass.h"
#include "engine/motion/kinematics.h"
#include "engine/motion/support_polygon.h"

namespace prep::cli {

std::vector<InfoSection>& info_sections() {
  static std::vector<InfoSection> all;
  return all;
}

ClipInfo clip_info(const MotionSet& set, const MotionClip& mc, const Params& params) {
  ClipInfo info;
  const Clip& clip = mc.clip;
  info.frames = clip.frame_count();
  info.fps = clip.fps;
  info.seconds = clip.fps > 0 ? static_cast<float>(info.frames) / clip.fps : 0.0f;
  if (info.frames == 0) return info;
  int left = 0, right = 0, inside = 0;
  std::vector<glm::vec3> positions, centroids;
  std::vector<glm::quat> rotations;
  for (int f = 0; f < info.frames; ++f) {
    const FrameContacts& contacts = mc.contacts.at(static_cast<size_t>(f));
    left += contacts[kLeft].any() ? 1 : 0;
    right += contacts[kRight].any() ? 1 : 0;
    if (!contacts[kLeft].any() && !contacts[kRight].any()) continue;  // in flight: no support polygon
    ++info.support_frames;
    forward_kinematics(*clip.skeleton, clip.frames[static_cast<size_t>(f)], positions, &rotations);
    const FootPoints feet = foot_points(*clip.skeleton, set.body, positions, rotations);
    const SupportPolygon polygon = support_polygon(feet, contacts, params.contacts);
    segment_centroids(*clip.skeleton, set.mass, positions, rotations, centroids);
    const glm::vec3 com = center_of_mass(set.mass, centroids);
    inside += polygon.contains(glm::vec2(com.x, com.z)) ? 1 : 0;
  }
  info.contact_left = static_cast<float>(left) / static_cast<float>(info.frames);
  info.contact_right = static_cast<float>(right) / static_cast<float>(info.frames);
  info.com_in_support = info.support_frames > 0 ? static_cast<float>(inside) / static_cast<float>(info.support_frames) : 0.0f;
  return info;
}

nlohmann::json describe_motion_set(const MotionSet& set, const Params& params) {
  nlohmann::json out;
  out["name"] = set.name;
  out["source"] = set.manifest_path.empty() ? "builtin" : set.manifest_path;
  out["skeleton"] = {{"joints", set.skeleton ? set.skeleton->size() : 0}};
  nlohmann::json clips = nlohmann::json::array();
  for (const MotionClip& mc : set.clips) {
    const ClipInfo info = clip_info(set, mc, params);
    nlohmann::json c = {{"name", mc.clip.name},
                        {"role", role_name(mc.role)},
                        {"frames", info.frames},
                        {"fps", info.fps},
                        {"seconds", info.seconds},
                        {"contact", {{"left", info.contact_left}, {"right", info.contact_right}}},
                        {"com_in_support", info.com_in_support},
                        {"support_frames", info.support_frames},
                        {"source", mc.source_file}};
    if (mc.cyclic) c["loop"] = {mc.loop_first, mc.loop_last};
    if (mc.target_frame >= 0) c["t_t"] = mc.target_frame;
    clips.push_back(std::move(c));
  }
  out["clips"] = std::move(clips);
  if (!set.warnings.empty()) out["warnings"] = set.warnings;
  auto& sections = info_sections();
  std::stable_sort(sections.begin(), sections.end(), [](const auto& a, const auto& b) { return a.order < b.order; });
  for (const InfoSection& s : sections) out[s.key] = s.build(set, params);
  return out;
}

void print_motion_set(std::ostream& out, const MotionSet& set, const nlohmann::json& d) {
  out << "motion set: " << set.name << " (" << d["source"].get<std::string>() << ")\n";
  out << "skeleton: " << d["skeleton"]["joints"].get<int>() << " joints\n";
  out << "clips: " << d["clips"].size() << "\n";
  char line[256];
  std::snprintf(line, sizeof line, "  %-22s %-12s %7s %6s %8s %9s %9s %15s\n", "name", "role", "frames", "fps", "seconds",
                "contact L", "contact R", "COM in support");
  out << line;
  for (const auto& c : d["clips"]) {
    std::snprintf(line, sizeof line, "  %-22s %-12s %7d %6.1f %8.2f %9.2f %9.2f %15.2f\n", c["name"].get<std::string>().c_str(),
                  c["role"].get<std::string>().c_str(), c["frames"].get<int>(), c["fps"].get<double>(), c["seconds"].get<double>(),
                  c["contact"]["left"].get<double>(), c["contact"]["right"].get<double>(), c["com_in_support"].get<double>());
    out << line;
  }
  out << "contact: fraction of the clip's frames with that foot's heel or toe on the floor.\n"
         "COM in support: fraction of the frames with a foot on the floor (frames in flight are left out) whose\n"
         "centre of mass projects inside the support polygon.\n";
  for (const std::string& w : set.warnings) out << "warning: " << w << "\n";
  for (const InfoSection& s : info_sections()) {
    if (!d.contains(s.key)) continue;
    out << s.key << ":\n";
    if (s.print)
      s.print(out, d[s.key]);
    else
      out << d[s.key].dump(2) << "\n";
  }
}

}  // namespace prep::cli

namespace {

prep::cli::RegisterCommand info_command(
    "info",
    "Describe a motion set: skeleton joint count; each clip's role, frames, fps, seconds, foot contact "
    "fractions and how often the centre of mass is over the support polygon",
    10, [](CLI::App& app) {
      struct Options {
        std::string motions;
        std::string params;
        bool json = false;
      };
      auto options = std::make_shared<Options>();
      app.add_option("--motions", options->motions,
                     "Motion-set manifest (JSON, e.g. assets/manifests/cmu31.json); default: the built-in library");
      app.add_option("--params", options->params, "Params JSON file (default: the built-in defaults)");
      app.add_flag("--json", options->json, "Print one JSON object instead of text");
      app.callback([options] {
        const prep::Params params = options->params.empty() ? prep::Params{} : prep::load_params(options->params);
        const prep::MotionSet set = options->motions.empty() ? prep::make_builtin_motion_set(params)
                                                             : prep::load_motion_set(options->motions, params);
        const nlohmann::json description = prep::cli::describe_motion_set(set, params);
        if (options->json)
          std::cout << description.dump(2) << "\n";
        else
          prep::cli::print_motion_set(std::cout, set, description);
      });
    });

}  // namespace
