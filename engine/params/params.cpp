#include "engine/params/params.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <sstream>
#include <nlohmann/json.hpp>
#include <type_traits>

#include "engine/util/error.h"
#include "engine/util/files.h"

namespace prep {
namespace {

using nlohmann::json;

// Each sub-struct lists its fields once; the same list drives JSON output, strict JSON input and the
// policy hash, so a field added here is saved, loaded and (where it matters) hashed without more code.
template <class F> void fields(ContactParams& p, F&& f) {
  f("height_on", p.height_on); f("height_off", p.height_off);
  f("speed_on", p.speed_on); f("speed_off", p.speed_off); f("foot_width", p.foot_width);
}
template <class F> void fields(GraphParams& p, F&& f) {
  f("window_s", p.window_s); f("threshold", p.threshold); f("blend_s", p.blend_s);
}
template <class F> void fields(ReferenceParams& p, F&& f) { f("legs_threshold", p.legs_threshold); }
template <class F> void fields(BlendParams& p, F&& f) {
  f("C_upper", p.C_upper); f("C_lower", p.C_lower); f("c_scale", p.c_scale);
  f("C_override", p.C_override); f("c_override", p.c_override); f("method", p.method);
}
template <class F> void fields(IkParams& p, F&& f) {
  f("knee_soft_start", p.knee_soft_start); f("reach_limit", p.reach_limit); f("release_s", p.release_s); f("pivot_speed", p.pivot_speed);
  f("max_root_drop", p.max_root_drop); f("drop_recovery_speed", p.drop_recovery_speed); f("enabled", p.enabled);
}
template <class F> void fields(BalanceParams& p, F&& f) {
  f("w_b", p.w_b); f("w_s", p.w_s); f("w_m", p.w_m); f("max_steps", p.max_steps);
  f("alpha_threshold", p.alpha_threshold); f("step_size", p.step_size); f("tolerance", p.tolerance);
  f("max_halvings", p.max_halvings); f("norm_smoothing", p.norm_smoothing);
  f("max_part_shift", p.max_part_shift); f("max_shift_speed", p.max_shift_speed); f("warm_start", p.warm_start);
  f("enabled", p.enabled);
}
template <class F> void fields(QuantizationParams& p, F&& f) {
  f("d_step", p.d_step); f("d_g_bins", p.d_g_bins); f("d_i_bins", p.d_i_bins);
  f("theta_g_step_deg", p.theta_g_step_deg); f("theta_g_bins", p.theta_g_bins);
  f("theta_i_step_deg", p.theta_i_step_deg); f("theta_i_bins", p.theta_i_bins);
  f("alpha_step", p.alpha_step); f("alpha_levels", p.alpha_levels); f("core_roles", p.core_roles);
  f("footsteps_per_action", p.footsteps_per_action); f("forced_top_level", p.forced_top_level);
}
template <class F> void fields(RewardParams& p, F&& f) {
  f("theta_norm_deg", p.theta_norm_deg); f("d_norm", p.d_norm); f("C_alpha", p.C_alpha);
  f("w_theta", p.w_theta); f("w_d", p.w_d); f("w_alpha", p.w_alpha);
  f("goal_radius", p.goal_radius); f("source_radius", p.source_radius);
}
template <class F> void fields(SarsaParams& p, F&& f) {
  f("learning_rate", p.learning_rate); f("discount", p.discount); f("epsilon", p.epsilon);
  f("convergence_fraction", p.convergence_fraction); f("convergence_episodes", p.convergence_episodes);
  f("update_tolerance", p.update_tolerance); f("seed", p.seed); f("max_steps", p.max_steps);
  f("threads", p.threads); f("max_episode_steps", p.max_episode_steps);
  f("source_at_goal_fraction", p.source_at_goal_fraction); f("far_start_range", p.far_start_range);
}
template <class F> void fields(RuntimeParams& p, F&& f) {
  f("alpha_sigma_s", p.alpha_sigma_s); f("fixed_dt", p.fixed_dt); f("launch_alpha", p.launch_alpha);
  f("preparation_range", p.preparation_range); f("relax_without_source", p.relax_without_source);
  f("kept_alpha", p.kept_alpha); f("tight_turn_deg_per_s", p.tight_turn_deg_per_s);
  f("waypoint_pass_radius", p.waypoint_pass_radius); f("anticipate_closing", p.anticipate_closing);
  f("end_turn_at_goal_bearing", p.end_turn_at_goal_bearing); f("keep_source_ahead", p.keep_source_ahead);
  f("level_per_source_bin", p.level_per_source_bin);
  f("make_for_ball_source", p.make_for_ball_source);
  f("keep_clear", p.keep_clear);
}
template <class F> void sections(Params& p, F&& f) {
  f("contacts", p.contacts); f("graph", p.graph); f("reference", p.reference); f("blend", p.blend);
  f("ik", p.ik); f("balance", p.balance); f("quantization", p.quantization); f("reward", p.reward);
  f("sarsa", p.sarsa); f("runtime", p.runtime);
}

template <class S> json section_to_json(S& s) {
  json j = json::object();
  fields(s, [&](const char* name, auto& value) { j[name] = value; });
  return j;
}

// What nlohmann's conversion lets through silently: a number past a float's range (1e39 becomes infinity,
// which params_to_json then writes as null), a fraction or an out-of-range integer in an integer field
// (truncated, wrapped, or undefined behaviour for a float past the integer's range). Each returns why the
// value cannot be read as the file says, or "": integer_problem before the conversion, float_problem after.
template <class T> std::string integer_problem(const json& j) {
  if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
    if (!j.is_number()) return "";  // the conversion reports the wrong type
    if (!j.is_number_integer()) return "must be an integer";
    const bool fits = j.is_number_unsigned()
                          ? j.get<std::uint64_t>() <= static_cast<std::uint64_t>(std::numeric_limits<T>::max())
                          : j.get<std::int64_t>() >= static_cast<std::int64_t>(std::numeric_limits<T>::min()) &&
                                (std::is_unsigned_v<T> ||
                                 j.get<std::int64_t>() <= static_cast<std::int64_t>(std::numeric_limits<T>::max()));
    if (!fits) return "is out of range for this field (" + std::to_string(std::numeric_limits<T>::min()) + " to " +
                      std::to_string(std::numeric_limits<T>::max()) + ")";
  }
  return "";
}

template <class T> std::string float_problem(const T& value) {
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(value)) return "is not a finite number within float range";
  } else if constexpr (std::is_same_v<T, std::map<std::string, float>>) {
    for (const auto& [key, v] : value)
      if (!std::isfinite(v)) return "has '" + key + "', which is not a finite number within float range";
  }
  return "";
}

template <class S> void section_from_json(const json& j, S& s, const std::string& file, const std::string& where) {
  if (!j.is_object()) throw InputError(file, "'" + where + "' must be an object");
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool known = false;
    fields(s, [&](const char* name, auto& value) {
      if (it.key() != name) return;
      known = true;
      auto refuse = [&](const std::string& problem) {
        throw InputError(file, "'" + where + "." + it.key() + "' " + problem + ": " + it.value().dump());
      };
      if (const std::string problem = integer_problem<std::decay_t<decltype(value)>>(it.value()); !problem.empty())
        refuse(problem);
      try {
        it.value().get_to(value);
      } catch (const json::exception&) {
        throw InputError(file, "'" + where + "." + it.key() + "' has the wrong type (" +
                                   std::string(it.value().type_name()) + ")");
      }
      if (const std::string problem = float_problem(value); !problem.empty()) refuse(problem);
    });
    if (!known) throw InputError(file, "unknown field '" + where + "." + it.key() + "'");
  }
}

}  // namespace

std::string params_to_json(const Params& params) {
  Params copy = params;
  json j = json::object();
  sections(copy, [&](const char* name, auto& section) { j[name] = section_to_json(section); });
  return j.dump(2) + "\n";
}

Params params_from_json(const std::string& text, const std::string& source_name) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    throw InputError(source_name, "invalid JSON at byte " + std::to_string(e.byte) + ": " + e.what());
  } catch (const json::exception& e) {  // a number past a double's range (1e400)
    throw InputError(source_name, std::string("invalid JSON: ") + e.what());
  }
  if (!j.is_object()) throw InputError(source_name, "params must be a JSON object");
  Params p;
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool known = false;
    sections(p, [&](const char* name, auto& section) {
      if (it.key() != name) return;
      known = true;
      section_from_json(it.value(), section, source_name, name);
    });
    if (!known) throw InputError(source_name, "unknown section '" + it.key() + "'");
  }
  check_params(p, source_name);
  return p;
}

namespace {

// A number's allowed range. Every number of the Params is at least 0 unless a rule says otherwise.
struct Range {
  const char* field;  // "section.field"
  double lo, hi;
  bool lo_open;       // lo itself not allowed
};
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr Range kRanges[] = {
    // Divided by, or a count of something there must be one of.
    {"runtime.fixed_dt", 0.0, 0.1, true},
    {"runtime.launch_alpha", 0.0, 1.0, true},
    {"runtime.kept_alpha", -kInf, 1.0, false},  // negative: resume at 0
    {"quantization.d_step", 0.0, kInf, true},
    {"quantization.theta_g_step_deg", 0.0, 360.0, true},
    {"quantization.theta_i_step_deg", 0.0, 360.0, true},
    {"quantization.alpha_step", 0.0, 1.0, true},
    {"quantization.d_g_bins", 1, kInf, false},
    {"quantization.d_i_bins", 1, kInf, false},
    {"quantization.theta_g_bins", 1, kInf, false},
    {"quantization.theta_i_bins", 1, kInf, false},
    {"quantization.alpha_levels", 2, kInf, false},
    {"quantization.footsteps_per_action", 1, kInf, false},
    {"sarsa.threads", 1, 256, false},
    {"sarsa.convergence_episodes", 1, kInf, false},
    {"sarsa.max_episode_steps", 1, kInf, false},
    {"sarsa.max_steps", 1, kInf, false},
    {"balance.max_steps", 0, 1000, false},
    {"balance.max_halvings", 0, 60, false},
    // Fractions and probabilities.
    {"sarsa.learning_rate", 0.0, 1.0, false},
    {"sarsa.discount", 0.0, 1.0, false},
    {"sarsa.epsilon", 0.0, 1.0, false},
    {"sarsa.convergence_fraction", 0.0, 1.0, false},
    {"sarsa.source_at_goal_fraction", 0.0, 1.0, false},
    {"ik.knee_soft_start", 0.0, 1.0, true},
    {"ik.reach_limit", 0.0, 1.0, true},
    {"balance.alpha_threshold", 0.0, 1.0, false},
};

std::string number_text(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

}  // namespace

void check_params(const Params& params, const std::string& source_name) {
  const json j = json::parse(params_to_json(params));
  for (const auto& [section, fields] : j.items()) {
    if (!fields.is_object()) continue;
    for (const auto& [field, value] : fields.items()) {
      if (!value.is_number()) continue;
      const std::string name = section + "." + field;
      Range r{nullptr, 0.0, kInf, false};
      for (const Range& k : kRanges)
        if (name == k.field) r = k;
      const double v = value.get<double>();
      const bool ok = std::isfinite(v) && (r.lo_open ? v > r.lo : v >= r.lo) && v <= r.hi;
      if (!ok)
        throw InputError(source_name, "'" + name + "' is " + number_text(v) + ", outside " + (r.lo_open ? "(" : "[") +
                                          number_text(r.lo) + ", " + number_text(r.hi) + "]");
    }
  }
  // The state space (Sec. 6.1): alpha is forced to 1 at the source, so the top level must be 1; the angle
  // bins must cover the whole turn.
  const QuantizationParams& q = params.quantization;
  if (std::abs(q.alpha_step * static_cast<float>(q.alpha_levels - 1) - 1.0f) > 1e-4f)
    throw InputError(source_name, "'quantization': (alpha_levels - 1) x alpha_step is " +
                                      number_text(q.alpha_step * static_cast<float>(q.alpha_levels - 1)) + ", must be 1");
  if (std::abs(q.theta_g_step_deg * static_cast<float>(q.theta_g_bins) - 360.0f) > 0.05f)
    throw InputError(source_name, "'quantization': theta_g_step_deg x theta_g_bins must be 360");
  if (std::abs(q.theta_i_step_deg * static_cast<float>(q.theta_i_bins) - 360.0f) > 0.05f)
    throw InputError(source_name, "'quantization': theta_i_step_deg x theta_i_bins must be 360");
}

Params load_params(const std::string& path) { return params_from_json(read_file(path), path); }

void save_params(const Params& params, const std::string& path) {
  write_file_atomic(path, params_to_json(params));
}

std::uint64_t policy_params_hash(const Params& params) {
  // FNV-1a over the canonical JSON of the sections a policy depends on. The blend's lower-body curve
  // matters because it changes the stride (Eq. 3-4) and so the action table the policy was trained on.
  Params copy = params;
  json j;
  j["quantization"] = section_to_json(copy.quantization);
  j["reward"] = section_to_json(copy.reward);
  json sarsa = section_to_json(copy.sarsa);
  sarsa.erase("threads");    // the thread count changes the run, not what the policy means
  sarsa.erase("max_steps");
  sarsa.erase("seed");       // another seed trains the same problem: its policy is as valid
  j["sarsa"] = sarsa;
  j["C_lower"] = copy.blend.C_lower;
  j["method"] = copy.blend.method;
  const std::string s = j.dump();
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace prep
