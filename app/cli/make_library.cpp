// prep make-library: regenerates the built-in motion library (BVH clips + manifest.json).
#include <iostream>

#include "app/cli/command.h"
#include "engine/library/builtin.h"
#include "engine/params/params.h"

namespace {
prep::cli::RegisterCommand make_library_command(
    "make-library", "Generate the built-in motion library as BVH files and a manifest", 20, [](CLI::App& app) {
      auto out = std::make_shared<std::string>("build/library");
      app.add_option("--out", *out, "output folder (created if missing)");
      app.callback([out] {
        const prep::Params params;
        const prep::MotionSet set = prep::make_builtin_motion_set(params);
        prep::write_builtin_library(set, *out);
        std::cout << "wrote " << set.clips.size() << " clips and manifest.json to " << *out << "\n";
        for (const prep::MotionClip& m : set.clips)
          std::cout << "  " << m.clip.name << " (" << prep::role_name(m.role) << "): " << m.clip.frame_count() << " frames at "
                    << m.clip.fps << " fps" << (m.cyclic ? ", loop" : "") << (m.target_frame >= 0 ? ", T_t " + std::to_string(m.target_frame) : "")
                    << "\n";
      });
    });
}
