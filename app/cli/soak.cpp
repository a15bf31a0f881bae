// prep soak: the world for hours of simulated time under goals, courses and Params changing, every tick
// checked (engine/world/soak.h); exit 1 on any violation.
//
//   prep soak --hours H --characters N [--seed S] [--json]
#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "app/cli/command.h"
#include "engine/world/soak.h"

namespace {

struct SoakCliOptions {
  double hours = 1.0;
  int characters = 100;
  std::uint64_t seed = 1;
  std::string cache;
  bool json = false;
};

void print_period(const prep::SoakPeriod& p) {
  const prep::SoakViolations& v = p.violations;
  std::fprintf(stderr,
               "hour %d: %.0f s simulated, %lld character-ticks, %d courses, %d goals moved, %d Params changes "
               "(%d refused), %d retrainings, %.1f MB resident, %.1f MB on the heap; violations %lld (pose %lld, feet %lld, root %lld, "
               "alpha %lld, stuck %lld, memory %lld)\n",
               p.hour, p.simulated_s, static_cast<long long>(p.character_ticks), p.courses, p.goals_moved, p.params_changes,
               p.params_refused, p.retrains, p.rss_mb, p.heap_mb, static_cast<long long>(v.total()), static_cast<long long>(v.bad_pose),
               static_cast<long long>(v.foot_below), static_cast<long long>(v.root_height), static_cast<long long>(v.alpha_range),
               static_cast<long long>(v.stuck), static_cast<long long>(v.memory));
  for (const std::string& s : p.first_violations) std::fprintf(stderr, "  %s\n", s.c_str());
}

prep::cli::RegisterCommand soak_command(
    "soak", "Run the world for hours of simulated time (goals, courses, Params changing) and check every tick", 95,
    [](CLI::App& app) {
      auto o = std::make_shared<SoakCliOptions>();
      app.add_option("--hours", o->hours, "Simulated hours (default 1)");
      app.add_option("--characters", o->characters, "Characters at once, in worlds of random courses (default 100)");
      app.add_option("--seed", o->seed, "Seed of the courses, goals and Params changes (default 1)");
      app.add_option("--policy-cache", o->cache, "Folder of cached policies (default: ~/.cache/prep)");
      app.add_flag("--json", o->json, "Print the report as JSON");
      app.callback([o] {
        prep::SoakOptions options;
        options.hours = o->hours;
        options.characters = o->characters;
        options.seed = o->seed;
        options.cache_dir = o->cache;
        const prep::SoakReport r = prep::run_soak(options, print_period);
        if (o->json) std::cout << prep::soak_json(r).dump(2) << "\n";
        std::fprintf(stderr,
                     "%d characters, %.1f s of wall time; the heap %.3f MB after the first minute, %.3f MB at the end "
                     "(resident %.1f / %.1f MB): %s\n",
                     r.characters, r.wall_s, r.heap_first_minute_mb, r.heap_end_mb, r.rss_first_minute_mb, r.rss_end_mb,
                     r.ok() ? "no violation" : "VIOLATIONS");
        if (!r.ok()) throw std::runtime_error("the soak found violations (listed above)");
      });
    });

}  // namespace
