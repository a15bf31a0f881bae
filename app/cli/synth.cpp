// prep synth: walking with preparation rising toward a target action (paper Sec. 5), written as BVH or glTF
// (by the extension of --out) to look at in Blender; --json prints per-frame metrics.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "app/cli/command.h"
#include "engine/interop/character_mesh.h"
#include "engine/interop/motion_export.h"
#include "engine/library/builtin.h"
#include "engine/motion/motion_set.h"
#include "engine/synthesis/preparation_run.h"

namespace {

struct SynthOptions {
  std::string motions;
  std::string target;
  std::string walk;
  std::string alpha_ramp = "0:1";
  float seconds = 3.0f;
  std::string method = "ours";
  std::string out;
  std::string params_file;
  bool json = false;
  bool with_mesh = false;
};

void parse_ramp(const std::string& text, float& a0, float& a1) {
  const size_t colon = text.find(':');
  try {
    if (colon == std::string::npos) throw std::invalid_argument("no colon");
    size_t used0 = 0, used1 = 0;
    const std::string s0 = text.substr(0, colon), s1 = text.substr(colon + 1);
    a0 = std::stof(s0, &used0);
    a1 = std::stof(s1, &used1);
    if (used0 != s0.size() || used1 != s1.size()) throw std::invalid_argument("trailing characters");
  } catch (const std::exception&) {
    throw std::invalid_argument("--alpha-ramp must read A0:A1 (e.g. 0:1), not \"" + text + "\"");
  }
  if (a0 < 0.0f || a0 > 1.0f || a1 < 0.0f || a1 > 1.0f) throw std::invalid_argument("--alpha-ramp values must lie in [0, 1]");
}

void run_synth(const SynthOptions& o) {
  if (!o.out.empty()) {
    // Check the output's format before the work (throws naming the path).
    if (prep::motion_format(o.out) == prep::MotionFormat::Bvh && o.with_mesh)
      throw std::invalid_argument("--with-mesh: a BVH holds no mesh (write .glb or .gltf)");
  } else if (o.with_mesh) {
    throw std::invalid_argument("--with-mesh needs --out FILE.glb or FILE.gltf");
  }
  prep::Params params = o.params_file.empty() ? prep::Params{} : prep::load_params(o.params_file);
  params.blend.method = o.method;
  float a0 = 0.0f, a1 = 1.0f;
  parse_ramp(o.alpha_ramp, a0, a1);
  if (!(o.seconds > 0.0f)) throw std::invalid_argument("--seconds must be positive");
  const prep::MotionSet set = o.motions.empty() ? prep::make_builtin_motion_set(params) : prep::load_motion_set(o.motions, params);

  // The target: a clip name, or a role (the first clip with that role and a T_t).
  int target = set.find(o.target);
  if (target < 0) {
    if (const auto role = prep::parse_role(o.target)) {
      for (size_t i = 0; i < set.clips.size() && target < 0; ++i) {
        if (set.clips[i].role == *role && set.clips[i].target_frame >= 0) target = static_cast<int>(i);
      }
    }
  }
  if (target < 0 || set.clips[static_cast<size_t>(target)].target_frame < 0) {
    std::string have;
    for (const auto& c : set.clips) {
      if (c.target_frame >= 0) have += (have.empty() ? "" : ", ") + c.clip.name + " (" + prep::role_name(c.role) + ")";
    }
    throw std::invalid_argument("--target \"" + o.target + "\" is no target motion of " + set.name + "; it has: " + have);
  }
  int walk = o.walk.empty() ? prep::find_cyclic_clip(set, prep::Role::Walk) : set.find(o.walk);
  if (walk < 0 || !set.clips[static_cast<size_t>(walk)].cyclic) {
    throw std::invalid_argument("no cyclic walk clip " + (o.walk.empty() ? std::string("in ") + set.name : "\"" + o.walk + "\""));
  }

  prep::PreparationRunOptions ro;
  ro.locomotion_clip = walk;
  const prep::MotionClip& target_clip = set.clips[static_cast<size_t>(target)];
  const int reference_frame = prep::scan_reference_frame(set, target_clip, params);
  ro.reference = target_clip.clip.frames[static_cast<size_t>(reference_frame)];
  ro.alpha_start = a0;
  ro.alpha_end = a1;
  ro.seconds = o.seconds;
  const prep::PreparationRun run = prep::run_preparation(set, params, ro);

  if (!o.out.empty()) {
    prep::Clip clip;
    clip.name = "synth_" + set.clips[static_cast<size_t>(target)].clip.name;
    clip.skeleton = set.skeleton;
    clip.fps = run.fps;
    clip.frames = run.frames;
    prep::SkinnedMesh mesh;
    if (o.with_mesh) mesh = prep::build_character_mesh(*set.skeleton, set.body);
    prep::write_clip(o.out, clip, o.with_mesh ? &mesh : nullptr);
  }

  int considered = 0, inside_before = 0, inside_after = 0, increased = 0, double_support = 0, double_inside = 0;
  float max_slide = 0.0f, max_shift = 0.0f;
  for (size_t i = 0; i < run.frames.size(); ++i) {
    const auto& r = run.reports[i];
    max_slide = std::max(max_slide, run.foot_slide[i]);
    if (r.alpha < params.balance.alpha_threshold || !r.has_support) continue;
    ++considered;
    inside_before += r.com_inside_before ? 1 : 0;
    inside_after += r.com_inside_after ? 1 : 0;
    increased += r.com_distance_after > r.com_distance_before ? 1 : 0;
    max_shift = std::max(max_shift, r.balance_shift);
    if (run.contacts[i][prep::kLeft].any() && run.contacts[i][prep::kRight].any()) {
      ++double_support;
      double_inside += r.com_inside_after ? 1 : 0;
    }
  }
  const auto fraction = [&](int k) { return considered > 0 ? static_cast<double>(k) / considered : 0.0; };
  if (o.json) {
    nlohmann::json frames = nlohmann::json::array();
    for (size_t i = 0; i < run.frames.size(); ++i) {
      const auto& r = run.reports[i];
      nlohmann::json f = {{"frame", i},
                          {"alpha", r.alpha},
                          {"w_root", r.w_root},
                          {"foot_slide", run.foot_slide[i]},
                          {"support", r.has_support},
                          {"optimized", r.balanced},
                          {"warm_started", r.warm_started},
                          {"steps", r.balance_steps},
                          {"balance_shift", r.balance_shift},
                          {"contacts", {{"left", {run.contacts[i][prep::kLeft].heel, run.contacts[i][prep::kLeft].toe}},
                                        {"right", {run.contacts[i][prep::kRight].heel, run.contacts[i][prep::kRight].toe}}}}};
      if (r.has_support) {
        f["com_distance_before"] = r.com_distance_before;
        f["com_distance_after"] = r.com_distance_after;
        f["com_inside_before"] = r.com_inside_before;
        f["com_inside_after"] = r.com_inside_after;
      }
      frames.push_back(std::move(f));
    }
    nlohmann::json out = {{"motions", set.name},
                          {"walk", set.clips[static_cast<size_t>(walk)].clip.name},
                          {"target", set.clips[static_cast<size_t>(target)].clip.name},
                          {"method", o.method},
                          {"reference_frame", reference_frame},
                          {"fps", run.fps},
                          {"summary",
                           {{"frames", run.frames.size()},
                            {"max_foot_slide", max_slide},
                            {"balance_frames", considered},
                            {"com_inside_before", fraction(inside_before)},
                            {"com_inside_after", fraction(inside_after)},
                            {"double_support_frames", double_support},
                            {"double_support_inside_after",
                             double_support > 0 ? static_cast<double>(double_inside) / double_support : 0.0},
                            {"max_balance_shift", max_shift},
                            {"distance_increased", increased}}},
                          {"frames", std::move(frames)}};
    std::cout << out.dump(1) << "\n";
  } else {
    std::printf("%s: %s -> %s, %s, %zu frames at %.0f fps, alpha %.2f -> %.2f\n", set.name.c_str(),
                set.clips[static_cast<size_t>(walk)].clip.name.c_str(), set.clips[static_cast<size_t>(target)].clip.name.c_str(),
                o.method.c_str(), run.frames.size(), run.fps, a0, a1);
    std::printf("largest foot slide in contact: %.2f mm/frame\n", 1000.0f * max_slide);
    std::printf("frames with alpha >= %.2f and support: %d; COM inside the support polygon %.1f%% before, %.1f%% after "
                "optimization; distance increased on %d\n",
                params.balance.alpha_threshold, considered, 100.0 * fraction(inside_before), 100.0 * fraction(inside_after),
                increased);
    std::printf("double support: %d of those frames, COM inside on %.1f%% after optimization; the optimizer moved a "
                "body part at most %.1f cm\n",
                double_support, double_support > 0 ? 100.0 * double_inside / double_support : 0.0, 100.0f * max_shift);
    if (!o.out.empty()) std::printf("wrote %s\n", o.out.c_str());
  }
}

prep::cli::RegisterCommand synth_command(
    "synth", "Synthesize walking with preparation rising toward a target action (Sec. 5); write BVH or glTF", 40,
    [](CLI::App& app) {
      auto o = std::make_shared<SynthOptions>();
      app.add_option("--motions", o->motions, "Motion-set manifest (JSON); default: the built-in library");
      app.add_option("--target", o->target, "Target motion: a clip name or a role (crawl, duck, jump, punch_left, ...)")
          ->required();
      app.add_option("--walk", o->walk, "Locomotion clip to loop (default: the first cyclic walk)");
      app.add_option("--alpha-ramp", o->alpha_ramp, "Level of preparation, ramped linearly A0:A1 over the run")
          ->capture_default_str();
      app.add_option("--seconds", o->seconds, "Duration of the run in seconds")->capture_default_str();
      app.add_option("--method", o->method, "ours (per-joint curves, Eq. 1) or linear (one weight, Fig. 6 top)")
          ->check(CLI::IsMember({"ours", "linear"}))
          ->capture_default_str();
      app.add_option("--out", o->out, "Write the synthesized motion to this file: .bvh, .glb or .gltf");
      app.add_flag("--with-mesh", o->with_mesh, "glTF only: add our skinned body, bound to the set's skeleton");
      app.add_option("--params", o->params_file, "Params JSON file");
      app.add_flag("--json", o->json, "Print per-frame alpha, COM distance to the support centre before/after "
                                      "optimization and foot slide as JSON");
      app.callback([o] { run_synth(*o); });
    });

}  // namespace
