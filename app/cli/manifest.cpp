// prep manifest: a folder of BVH takes -> a motion-set manifest (engine/scan/folder_scan.h), checked by
// loading it back, with a table (or --json) of every guess, its evidence and confidence, and what the set
// lacks.
//
//   prep manifest --folder DIR [--out my_set.json] [--json]
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "app/cli/command.h"
#include "engine/control/action_effects.h"
#include "engine/graph/motion_graph.h"
#include "engine/motion/motion_set.h"
#include "engine/scan/folder_scan.h"
#include "engine/util/files.h"

namespace {

struct ManifestOptions {
  std::string folder, out;
  bool json = false;
};

void run(const ManifestOptions& o) {
  const prep::Params params;
  const prep::FolderScan scan = prep::scan_motion_folder(o.folder, params);
  const std::string out = o.out.empty() ? scan.name + ".json" : o.out;
  prep::write_file_atomic(out, prep::scan_manifest_json(scan, out).dump(2) + "\n");

  // The check: the manifest loads, its graph builds, and the controller finds its core motions.
  const prep::MotionSet set = prep::load_motion_set(out, params);
  const prep::MotionGraph graph = prep::MotionGraph::build(set, params.graph);
  std::string core;
  for (const prep::MotionClip* c : prep::default_core_clips(set)) core += (core.empty() ? "" : ", ") + c->clip.name;

  if (o.json) {
    nlohmann::json j = prep::scan_report_json(scan);
    j["manifest"] = out;
    j["check"] = {{"clips", set.clips.size()}, {"graph_nodes", graph.nodes().size()}, {"graph_edges", graph.edges().size()},
                  {"core_motions", core}};
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::cout << prep::scan_report_text(scan) << "\n"
            << out << ": written and loaded back: " << set.clips.size() << " clips, a motion graph of " << graph.nodes().size()
            << " nodes and " << graph.edges().size() << " edges; the controller's core motions: " << core << "\n";
}

prep::cli::RegisterCommand manifest_command(
    "manifest", "Scan a folder of BVH takes into a motion-set manifest: units, roles, loops, T_t, steered turns", 72,
    [](CLI::App& app) {
      auto o = std::make_shared<ManifestOptions>();
      app.add_option("--folder", o->folder, "The folder of .bvh files (its subfolders are not read)")->required();
      app.add_option("--out", o->out, "The manifest to write (default: <folder name>.json here)");
      app.add_flag("--json", o->json, "Print what was found as JSON instead of a table");
      app.callback([o] { run(*o); });
    });

}  // namespace
