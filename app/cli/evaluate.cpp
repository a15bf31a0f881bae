// prep evaluate: runs scenarios headless with their auto launches under each method (ours, linear, naive)
// and prints the measures of engine/world/evaluation.h: a text table, JSON, or the README's markdown tables;
// optionally a PNG plot per scenario of the user's alpha over time, one line per method.
// prep evaluate --random N --seed S: N random courses (engine/world/courses.h) instead, run with our method
// on both cores, and the measures of engine/world/course_evaluation.h per course, in total, and as
// pass/fail acceptance checks.
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "app/cli/command.h"
#include "engine/control/action_effects.h"
#include "engine/util/error.h"
#include "engine/util/files.h"
#include "engine/util/plot.h"
#include "engine/world/course_evaluation.h"
#include "engine/world/courses.h"
#include "engine/world/evaluation.h"
#include "engine/world/policy_cache.h"
#include "engine/world/world.h"

namespace {

struct Options {
  std::vector<std::string> scenarios;
  std::vector<std::string> methods{"ours", "linear", "naive"};
  std::string motions, params, cache, plot_dir;
  float seconds = 60.0f;
  bool json = false, markdown = false;
  bool vary_sizes = false;
  bool random_given = false;  // --random N: N random courses instead of --scenario
  int random = 0;
  std::uint64_t seed = 1;
  int threads = 0;  // 0: one per core
  std::string save_courses;  // folder to write the random courses to as scenario files
};

std::string fixed(double v, int decimals) {
  if (!std::isfinite(v)) return "-";
  char b[32];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  return b;
}

// The user's launches of a run, one value each, joined by " / ".
template <typename F>
std::string per_launch(const prep::Evaluation& e, F value, int decimals) {
  std::string out;
  for (const prep::LaunchEvaluation& l : e.characters[static_cast<size_t>(e.user)].launches)
    out += (out.empty() ? "" : " / ") + fixed(value(l), decimals);
  return out.empty() ? "-" : out;
}

std::string launch_actions(const prep::Evaluation& e) {
  std::string out;
  for (const prep::LaunchEvaluation& l : e.characters[static_cast<size_t>(e.user)].launches)
    out += (out.empty() ? "" : ", ") + std::string(prep::target_action_name(l.action));
  return out.empty() ? "none" : out;
}

std::string goal_cell(const prep::Evaluation& e) {
  const prep::CharacterEvaluation& u = e.characters[static_cast<size_t>(e.user)];
  return u.reached_goal ? "yes, " + fixed(u.time_to_goal_s, 2) + " s" : "no";
}

// One row per run: the scenario x method x metric table (the user's launches; frame metrics over every
// character).
std::string markdown_table(const std::vector<prep::Evaluation>& runs) {
  std::ostringstream o;
  o << "| scenario | motions | method | goal | user's launches | alpha at launch | prep lead (s) | peak decel (m/s^2) "
       "| foot skate (cm/frame) | COM in support | pose plausibility (cm) | synthesis (us/frame) |\n"
    << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const prep::Evaluation& e : runs) {
    const prep::FrameTotals t = e.totals();
    o << "| " << e.scenario << " | " << e.motions << " | " << prep::method_name(e.method) << " | " << goal_cell(e) << " | "
      << launch_actions(e) << " | " << per_launch(e, [](const auto& l) { return l.alpha_at_launch; }, 2) << " | "
      << per_launch(e, [](const auto& l) { return l.prep_lead_s; }, 2) << " | "
      << per_launch(e, [](const auto& l) { return l.peak_decel_mps2; }, 1) << " | " << fixed(t.foot_skate_cm_per_frame(), 3)
      << " | " << fixed(t.com_in_support(), 3) << " | " << fixed(t.pose_plausibility_cm(), 2) << " | "
      << fixed(e.synthesis_us_per_frame, 1) << " |\n";
  }
  return o.str();
}

// The acceptance checks, per scenario, where its three methods were run: ours' peak deceleration at most
// half of naive's at every launch (matched in order), lead >= 0.5 s, skate <= 0.3 cm/frame, COM in support
// >= 0.95, plausibility below linear's.
std::string markdown_checks(const std::vector<prep::Evaluation>& runs) {
  std::map<std::string, std::map<std::string, const prep::Evaluation*>> by;
  std::vector<std::string> order;
  for (const prep::Evaluation& e : runs) {
    const std::string key = e.scenario + " (" + e.motions + ")";
    if (!by.count(key)) order.push_back(key);
    by[key][prep::method_name(e.method)] = &e;
  }
  std::ostringstream o;
  o << "| scenario | decel ours <= naive / 2 | lead >= 0.5 s | skate <= 0.3 | COM >= 0.95 | plausibility ours < linear |\n"
    << "|---|---|---|---|---|---|\n";
  auto mark = [](bool ok) { return ok ? "yes" : "**no**"; };
  for (const std::string& key : order) {
    const auto& m = by[key];
    if (!m.count("ours")) continue;
    const prep::Evaluation& ours = *m.at("ours");
    const auto& ul = ours.characters[static_cast<size_t>(ours.user)].launches;
    std::string decel = "-";
    if (m.count("naive")) {
      const auto& nl = m.at("naive")->characters[static_cast<size_t>(m.at("naive")->user)].launches;
      // Each of ours' launches against naive's at the same object (or opponent); one naive never made
      // cannot be compared (it walked past).
      bool ok = !ul.empty();
      std::string ratios;
      for (const prep::LaunchEvaluation& l : ul) {
        const prep::LaunchEvaluation* match = nullptr;
        for (const prep::LaunchEvaluation& n : nl)
          if (!match && n.action == l.action && n.object == l.object && n.target_character == l.target_character) match = &n;
        std::string cell = "naive made none";
        if (match) {
          ok = ok && l.peak_decel_mps2 <= 0.5f * match->peak_decel_mps2;
          cell = fixed(match->peak_decel_mps2 > 0 ? l.peak_decel_mps2 / match->peak_decel_mps2 : NAN, 2);
        }
        ratios += (ratios.empty() ? "" : " / ") + std::string(prep::target_action_name(l.action)) + " " + cell;
      }
      decel = std::string(mark(ok)) + " (ours/naive: " + (ratios.empty() ? "-" : ratios) + ")";
    }
    bool lead = !ul.empty();
    for (const auto& l : ul) lead = lead && l.prep_lead_s >= 0.5f;
    const prep::FrameTotals t = ours.totals();
    std::string plaus = "-";
    if (m.count("linear"))
      plaus = std::string(mark(t.pose_plausibility_cm() < m.at("linear")->totals().pose_plausibility_cm())) + " (" +
              fixed(t.pose_plausibility_cm(), 2) + " vs " + fixed(m.at("linear")->totals().pose_plausibility_cm(), 2) + ")";
    o << "| " << key << " | " << decel << " | " << mark(lead) << " | " << mark(t.foot_skate_cm_per_frame() <= 0.3) << " ("
      << fixed(t.foot_skate_cm_per_frame(), 3) << ") | " << mark(t.com_in_support() >= 0.95) << " (" << fixed(t.com_in_support(), 3)
      << ") | " << plaus << " |\n";
  }
  return o.str();
}

std::string text_report(const prep::Evaluation& e) {
  std::ostringstream o;
  const prep::FrameTotals t = e.totals();
  o << e.scenario << " (" << e.motions << "), " << prep::method_name(e.method) << ": " << fixed(e.seconds, 2) << " s, goal "
    << goal_cell(e) << "\n";
  for (const prep::CharacterEvaluation& c : e.characters)
    for (const prep::LaunchEvaluation& l : c.launches) {
      char line[256];
      std::snprintf(line, sizeof line,
                    "  %6.2f s  character %d  %-11s alpha_at_launch %.2f  prep_lead %.2f s  peak_decel %5.1f m/s^2  "
                    "speed %.2f m/s  min clearance %.1f cm\n",
                    l.time, c.index, prep::target_action_name(l.action), l.alpha_at_launch, l.prep_lead_s, l.peak_decel_mps2,
                    l.speed_at_launch_mps, 100.0 * l.min_clearance);
      o << line;
      if (l.action == prep::TargetAction::Kick) o << "           the foot meets the ball " << fixed(100.0 * l.strike_gap, 1) << " cm from its surface\n";
    }
  const prep::ClearanceSummary& cl = e.clearance;
  o << "  clearance: " << cl.object_frames << " frames with a body more than 1 cm inside an object, " << cl.character_frames
    << " with bodies overlapping more than 2 cm; nearest to an object: " << (cl.min_object_what.empty() ? "-" : cl.min_object_what)
    << "; nearest between bodies: " << (cl.min_character_what.empty() ? "-" : cl.min_character_what) << "\n";
  o << "  foot skate " << fixed(t.foot_skate_cm_per_frame(), 3) << " cm/frame, COM in support " << fixed(t.com_in_support(), 3)
    << " (" << t.balance_frames << " frames with alpha >= 0.3), pose plausibility " << fixed(t.pose_plausibility_cm(), 2)
    << " cm, synthesis " << fixed(e.synthesis_us_per_frame, 1) << " us/frame\n";
  return o.str();
}

std::uint32_t method_colour(prep::EvaluationMethod m) {
  switch (m) {
    case prep::EvaluationMethod::Ours: return 0x1f5fbf;
    case prep::EvaluationMethod::Linear: return 0xe07b00;
    case prep::EvaluationMethod::Naive: return 0x808080;
  }
  return 0;
}

void plot_alpha(const std::string& path, const std::vector<const prep::Evaluation*>& runs) {
  std::vector<prep::PlotSeries> series;
  for (const prep::Evaluation* e : runs) {
    prep::PlotSeries s;
    s.rgb = method_colour(e->method);
    s.label = prep::method_name(e->method);
    const prep::CharacterEvaluation& u = e->characters[static_cast<size_t>(e->user)];
    for (size_t k = 0; k < e->times.size() && k < u.alpha.size(); ++k) {
      s.x.push_back(e->times[k]);
      s.y.push_back(u.alpha[k]);
    }
    for (const prep::LaunchEvaluation& l : u.launches) s.marks.push_back(l.time);
    series.push_back(std::move(s));
  }
  prep::PlotOptions o;
  o.width = 900;
  o.height = 360;
  o.title = "alpha: " + runs.front()->scenario + " (" + runs.front()->motions + ")";
  o.x_label = "time (s); dots: launches";
  o.y_label = "level of preparation";
  o.y_min = -0.05;
  o.y_max = 1.05;
  prep::write_line_plot_png(path, series, o);
}

std::string file_stem(const std::string& s) {
  std::string out;
  for (char c : s) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-') ? c : '_';
  return out;
}

// --- Random courses ----------------------------------------------------------------------------------------

// The Params file random courses run with: --params (made absolute, so that a course saved as a scenario
// file finds it from its own folder), else for a manifest the controller its shipped scenarios name
// (assets/scenarios/controller_<manifest name>.json) if there is one; "" for the defaults.
std::string random_params_file(const Options& o, const std::string& motions) {
  if (!o.params.empty()) return std::filesystem::absolute(o.params).string();
  if (motions == "builtin") return "";
  const std::string controller =
      prep::source_dir() + "/assets/scenarios/controller_" + std::filesystem::path(motions).stem().string() + ".json";
  return std::filesystem::exists(controller) ? controller : "";
}

std::string launch_cells(const prep::CourseEvaluation& e) {
  std::string out;
  for (const prep::CourseLaunch& l : e.launches)
    out += (out.empty() ? "" : ", ") + std::string(prep::target_action_name(l.action)) + " " + fixed(l.alpha_at_launch, 2) + "/" +
           (l.alpha_at_1m >= 0.0f ? fixed(l.alpha_at_1m, 2) : std::string("-"));
  return out.empty() ? "none" : out;
}

std::string course_text(const prep::CourseEvaluation& e) {
  std::ostringstream o;
  float kept = NAN;
  for (const prep::KeptPreparation& k : e.kept) kept = std::isnan(kept) ? k.min_alpha : std::min(kept, k.min_alpha);
  float relax = NAN;
  for (float r : e.relax_times) relax = std::isnan(relax) ? r : std::max(relax, r);
  o << e.name << ": " << e.description << "\n"
    << "  goal " << (e.reached_goal ? "yes, " + fixed(e.goal_time, 2) + " s" : "no") << " (run " << fixed(e.seconds, 1)
    << " s, route " << fixed(e.route_length, 1) << " m)  path ratio " << fixed(e.path_ratio, 3) << "  objects left "
    << e.objects_unused << "/" << e.objects << "\n"
    << "  launches (alpha at launch/at 1 m): " << launch_cells(e) << "\n"
    << "  kept preparation min " << fixed(kept, 2) << " (" << e.kept.size() << " close pairs)  no-source alpha median "
    << fixed(e.no_source_median(), 3) << " mean " << fixed(e.no_source_mean(), 3) << "  relax max " << fixed(relax, 2) << " s ("
    << e.unrelaxed_episodes << " unrelaxed)  circling " << fixed(e.circling_seconds, 1) << " s (largest turn near a goal "
    << fixed(e.max_visit_turn_deg, 0) << " deg)  turn reversals " << e.turn_reversals << " (most in "
    << fixed(prep::course_metric::kWeaveWindow, 0) << " s: " << e.most_reversals_in_window << ")\n";
  return o.str();
}

std::string totals_text(const prep::CourseTotals& t) {
  std::ostringstream o;
  auto pct = [](int part, int whole) { return whole > 0 ? fixed(100.0 * part / whole, 1) + "%" : std::string("-"); };
  auto line = [&o](const std::string& label, const std::string& value) {
    char b[48];
    std::snprintf(b, sizeof b, "  %-29s", label.c_str());
    o << b << value << "\n";
  };
  o << "total over " << t.courses << " courses:\n";
  line("goal reached", std::to_string(t.goals) + "/" + std::to_string(t.courses) + " (" + pct(t.goals, t.courses) + ")");
  line("alpha at launch >= " + fixed(prep::course_metric::kLaunchAlpha, 2),
       std::to_string(t.launches_prepared) + "/" + std::to_string(t.launches) + " launches (" + pct(t.launches_prepared, t.launches) + ")");
  line("alpha at 1 m >= " + fixed(prep::course_metric::kAlpha1m, 2),
       std::to_string(t.prepared_1m) + "/" + std::to_string(t.measured_1m) + " measured (" + pct(t.prepared_1m, t.measured_1m) + ")");
  line("objects never acted on", std::to_string(t.objects_unused) + "/" + std::to_string(t.objects));
  line("path ratio", "median " + fixed(t.path_median, 3) + ", p95 " + fixed(t.path_p95, 3));
  line("alpha, no source in range", "median " + fixed(t.no_source_median, 3) + ", mean " + fixed(t.no_source_mean, 3));
  line("relaxing below 0.1", "median " + fixed(t.relax_median, 2) + " s, max " + fixed(t.relax_max, 2) + " s (" +
                                 std::to_string(t.unrelaxed_episodes) + " episodes ended unrelaxed)");
  line("kept preparation (< 3 m)", std::to_string(t.kept_pairs) + " pairs, lowest alpha min " + fixed(t.kept_min, 2) +
                                       ", median " + fixed(t.kept_median, 2));
  line("circling", std::to_string(t.circling_courses) + " courses (" + fixed(t.circling_seconds, 1) + " s)");
  line("weaving", std::to_string(t.weaving_courses) + " courses; turn reversals " + fixed(t.reversals_per_minute, 2) +
                      " a minute");
  line("swerving", std::to_string(t.swerving_approaches) + "/" + std::to_string(t.approaches) + " approaches swung more than " +
                       fixed(prep::course_metric::kSwerveDeg, 0) + " degrees off their source");
  line("body inside an object > 1 cm", std::to_string(t.penetrating_courses) + " courses; deepest " +
                                           (t.min_object_what.empty() ? std::string("-") : t.min_object_what));
  line("bodies overlapping > 2 cm", std::to_string(t.overlapping_courses) + " courses; deepest " +
                                        (t.min_character_what.empty() ? std::string("-") : t.min_character_what));
  o << "checks:\n";
  for (const prep::CourseCheck& c : t.checks) o << "  " << (c.pass ? "pass" : "FAIL") << "  " << c.name << ": " << c.measure << "\n";
  o << (t.pass() ? "all checks pass\n" : "some checks fail\n");
  return o.str();
}

void run_random(const Options& o) {
  if (o.random <= 0) throw std::invalid_argument("--random must be a positive number of courses (got " + std::to_string(o.random) + ")");
  const std::string motions = o.motions.empty() ? "builtin" : o.motions;
  if (motions != "builtin") {
    const std::string path = motions.front() == '/' ? motions : prep::source_dir() + "/" + motions;
    if (!std::filesystem::is_regular_file(path))
      throw prep::InputError("--motions", "no motion set '" + motions + "' (\"builtin\" or a manifest path)");
  }
  prep::CourseOptions options;
  options.seed = o.seed;
  options.motions = motions;
  options.params_file = random_params_file(o, motions);
  prep::Scenario probe;  // what the courses share: their motion set and Params
  probe.motions = options.motions;
  probe.params_file = options.params_file;
  const prep::Params params = prep::load_scenario_params(probe);
  const std::string cache = o.cache.empty() ? prep::default_policy_cache_dir() : o.cache;
  bool trained = false;
  const auto assets = prep::prepare_world_assets(probe, params, cache, &trained);
  if (!o.json && trained) std::cerr << "trained a policy for " << assets->set->name << " (cached in " << cache << ")\n";
  options.actions = prep::actions_of(*assets);
  options.reach = prep::reaches_of(*assets);
  options.vary_sizes = o.vary_sizes;
  options.heights = prep::heights_of(*assets);
  const std::vector<prep::Scenario> courses = prep::make_courses(options, o.random);
  if (!o.save_courses.empty()) {
    std::filesystem::create_directories(o.save_courses);
    for (const prep::Scenario& s : courses)
      prep::write_file_atomic((std::filesystem::path(o.save_courses) / (s.name + ".json")).string(), prep::scenario_json(s));
  }
  const int threads = o.threads > 0 ? o.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const std::vector<prep::CourseEvaluation> runs = prep::evaluate_courses(courses, assets, threads);
  const prep::CourseTotals totals = prep::course_totals(runs);
  if (o.json) {
    nlohmann::json j;
    j["seed"] = o.seed;
    j["motions"] = assets->set->name;
    j["params"] = options.params_file.empty() ? nlohmann::json(nullptr) : nlohmann::json(options.params_file);
    j["courses"] = nlohmann::json::array();
    for (const prep::CourseEvaluation& e : runs) j["courses"].push_back(prep::course_json(e));
    j["total"] = prep::course_totals_json(totals);
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::cout << o.random << " random courses, seed " << o.seed << ", motions " << assets->set->name
            << (options.params_file.empty() ? "" : ", params " + options.params_file) << "\n";
  for (const prep::CourseEvaluation& e : runs) std::cout << course_text(e);
  std::cout << totals_text(totals);
}

void run(const Options& o) {
  if (o.random_given) return run_random(o);
  if (o.scenarios.empty()) throw std::invalid_argument("give --scenario FILE (or --random N for random courses)");
  std::vector<prep::EvaluationMethod> methods;
  for (const std::string& name : o.methods) {
    const auto m = prep::parse_method(name);
    if (!m) throw prep::InputError("--method", "unknown method '" + name + "' (ours, linear or naive)");
    methods.push_back(*m);
  }
  if (!(o.seconds > 0.0f)) throw std::invalid_argument("--seconds must be positive");
  const std::string cache = o.cache.empty() ? prep::default_policy_cache_dir() : o.cache;
  const bool quiet = o.json || o.markdown;
  std::vector<prep::Evaluation> runs;
  std::map<std::string, std::string> baselines;  // per motion set: its core clips' own foot skate
  for (const std::string& file : o.scenarios) {
    prep::Scenario scenario = prep::load_scenario(file);
    if (!o.motions.empty()) scenario.motions = o.motions;
    const prep::Params base = o.params.empty() ? prep::load_scenario_params(scenario) : prep::load_params(o.params);
    const auto set = prep::load_scenario_motions(scenario, base);
    const prep::EvaluationReference reference(*set);
    if (!baselines.count(set->name)) {
      std::string line;
      for (const prep::MotionClip* c : prep::core_clips(*set, base.quantization))
        line += (line.empty() ? "" : ", ") + c->clip.name + " " + fixed(prep::clip_foot_skate_cm_per_frame(*set, *c, reference), 3);
      baselines[set->name] = line;
    }
    std::vector<const prep::Evaluation*> scenario_runs;
    const size_t first = runs.size();
    for (prep::EvaluationMethod m : methods) {
      const prep::Params p = prep::method_params(m, base);
      auto assets = std::make_shared<prep::WorldAssets>(prep::make_world_assets(set, p));
      bool trained = false;
      assets->policy = prep::load_or_train_policy(*assets->set, *assets->graph, p, cache, {}, &trained);
      if (!quiet && trained) std::cerr << "trained a policy for " << scenario.name << " / " << prep::method_name(m) << " (cached in " << cache << ")\n";
      runs.push_back(prep::evaluate_scenario(scenario, assets, reference, m, o.seconds));
      if (!quiet) std::cout << text_report(runs.back());
    }
    for (size_t k = first; k < runs.size(); ++k) scenario_runs.push_back(&runs[k]);
    if (!o.plot_dir.empty()) {
      const std::string path = o.plot_dir + "/alpha_" + file_stem(scenario.name) + ".png";
      plot_alpha(path, scenario_runs);
      if (!quiet) std::cout << "alpha plot: " << path << "\n";
    }
  }
  if (o.json) {
    if (runs.size() == 1) {
      std::cout << prep::evaluation_json(runs.front()).dump(2) << "\n";
    } else {
      nlohmann::json all = nlohmann::json::array();
      for (const prep::Evaluation& e : runs) all.push_back(prep::evaluation_json(e));
      std::cout << all.dump(2) << "\n";
    }
  } else if (o.markdown) {
    std::cout << markdown_table(runs) << "\n";
    for (const auto& [motions, line] : baselines)
      std::cout << "Foot skate of the recorded core clips of " << motions << " (cm/frame, same measure): " << line << "\n\n";
    std::cout << markdown_checks(runs);
  }
}

prep::cli::RegisterCommand evaluate_command(
    "evaluate",
    "Measure a scenario's motion under ours / linear / naive: goal, per launch alpha, preparation lead and peak "
    "deceleration, foot skate, COM in support, pose plausibility, synthesis time; or, with --random N, "
    "N random courses with acceptance checks",
    45, [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      auto* scenario = app.add_option("--scenario", o->scenarios, "Scenario JSON (repeat for several)");
      auto* method = app.add_option("--method", o->methods, "ours, linear or naive (repeat or comma-separate; default all three)")
                         ->delimiter(',');
      auto* random = app.add_option("--random", o->random,
                                    "Run N random courses (engine/world/courses.h) with our method instead of --scenario");
      app.add_option("--seed", o->seed, "Seed of the random courses (default 1): course k of a seed is always the same")
          ->needs(random);
      app.add_option("--threads", o->threads, "Random courses run on this many threads (default: one per core)")
          ->check(CLI::Range(0, 256))
          ->needs(random);
      app.add_flag("--vary-sizes", o->vary_sizes,
                   "Random courses with obstacles of varied width, depth and height (those the motion set can pass)")
          ->needs(random);
      app.add_option("--save-courses", o->save_courses,
                     "Also write each random course to DIR/random-<seed>-<k>.json (a scenario for prep run or prep-demo)")
          ->needs(random);
      app.add_option("--motions", o->motions, "Motion set instead of the scenario's (\"builtin\" or a manifest path)");
      app.add_option("--params", o->params,
                     "Params JSON (default: the scenario's \"params\", else the defaults; random courses on a manifest "
                     "M.json: assets/scenarios/controller_M.json if there is one)");
      auto* seconds = app.add_option("--seconds", o->seconds, "Longest run (s, default 60); a run ends 1 s after the goal is reached");
      app.add_option("--policy-cache", o->cache, "Folder of cached policies (default: $PREP_CACHE_DIR or ~/.cache/prep)");
      auto* plot = app.add_option("--plot-dir", o->plot_dir, "Write DIR/alpha_<scenario>.png: the user's alpha over time per method");
      auto* json = app.add_flag("--json", o->json, "Print JSON: one run's object, or an array of them");
      auto* markdown = app.add_flag("--markdown", o->markdown, "Print the results and acceptance tables in markdown")->excludes(json);
      random->excludes(scenario)->excludes(method)->excludes(seconds)->excludes(plot)->excludes(markdown);
      app.callback([o, random] {
        o->random_given = random->count() > 0;
        run(*o);
      });
    });

}  // namespace
