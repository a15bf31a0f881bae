// `prep info` sections of the motion graph (Sec. 4.1) and the targets' reference postures (Sec. 4.2):
// "graph": {"nodes": [{"name", "role", "core"}], "edges": N, "next": {"<motion>": [...]}, "build_seconds", ...}
// "targets": [{"name", "action", "t_t", "reference_frame", "conditions": {...}}]
#include <cstdio>
#include <ostream>

#include "app/cli/info.h"
#include "engine/graph/motion_graph.h"
#include "engine/graph/reference_posture.h"

namespace {

using nlohmann::json;

json graph_section(const prep::MotionSet& set, const prep::Params& params) {
  const prep::MotionGraph graph = prep::MotionGraph::build(set, params.graph);
  json nodes = json::array();
  for (const prep::GraphNode& n : graph.nodes()) nodes.push_back({{"name", n.name}, {"role", prep::role_name(n.role)}, {"core", n.core}});
  json next = json::object();
  for (size_t i = 0; i < graph.nodes().size(); ++i) {
    json list = json::array();
    for (int m : graph.next(static_cast<int>(i))) list.push_back(graph.nodes()[static_cast<size_t>(m)].name);
    next[graph.nodes()[i].name] = std::move(list);
  }
  int forced = 0, loops = 0;
  for (const prep::GraphEdge& e : graph.edges()) {
    forced += e.forced ? 1 : 0;
    loops += e.loop ? 1 : 0;
  }
  return {{"nodes", nodes},
          {"edges", graph.edges().size()},
          {"next", next},
          {"loop_edges", loops},
          {"forced_edges", forced},
          {"window_frames", graph.window_frames()},
          {"build_seconds", graph.build_seconds()}};
}

void print_graph(std::ostream& out, const json& g) {
  int core = 0;
  for (const auto& n : g["nodes"]) core += n["core"].get<bool>() ? 1 : 0;
  char line[256];
  std::snprintf(line, sizeof line, "  %zu nodes (%d core), %d edges (%d loops, %d forced above the threshold), built in %.1f ms\n",
                g["nodes"].size(), core, g["edges"].get<int>(), g["loop_edges"].get<int>(), g["forced_edges"].get<int>(),
                1000.0 * g["build_seconds"].get<double>());
  out << line;
  for (const auto& n : g["nodes"]) {
    const std::string name = n["name"].get<std::string>();
    out << "  " << (n["core"].get<bool>() ? "[core] " : "       ") << name << " -> ";
    bool first = true;
    for (const auto& m : g["next"][name]) {
      out << (first ? "" : ", ") << m.get<std::string>();
      first = false;
    }
    out << "\n";
  }
}

json targets_section(const prep::MotionSet& set, const prep::Params& params) {
  json out = json::array();
  for (const prep::ReferencePosture& r : prep::find_reference_postures(set, params)) {
    const prep::MotionClip& mc = set.clips[static_cast<size_t>(r.clip)];
    out.push_back({{"name", mc.clip.name},
                   {"action", prep::role_name(mc.role)},
                   {"t_t", r.t_t},
                   {"reference_frame", r.frame},
                   {"found", r.found},
                   {"legs_distance", r.legs_distance},
                   {"conditions", {{"com_in_support", r.com_in_support}, {"same_contacts", r.same_contacts}, {"legs_close", r.legs_close}}}});
  }
  return out;
}

void print_targets(std::ostream& out, const json& t) {
  char line[256];
  std::snprintf(line, sizeof line, "  %-22s %-12s %5s %5s  %-5s %-5s %-5s\n", "name", "action", "T_t", "T_p", "COM", "feet", "legs");
  out << line;
  for (const auto& r : t) {
    const auto& c = r["conditions"];
    std::snprintf(line, sizeof line, "  %-22s %-12s %5d %5d  %-5s %-5s %-5s%s\n", r["name"].get<std::string>().c_str(),
                  r["action"].get<std::string>().c_str(), r["t_t"].get<int>(), r["reference_frame"].get<int>(),
                  c["com_in_support"].get<bool>() ? "yes" : "no", c["same_contacts"].get<bool>() ? "yes" : "no",
                  c["legs_close"].get<bool>() ? "yes" : "no", r["found"].get<bool>() ? "" : "  (none qualified: T_0)");
    out << line;
  }
  out << "  T_p: scanning back from T_t, the first frame with the COM over the support polygon, the same feet down\n"
         "  as T_0 and legs within reference.legs_threshold of T_0 (paper Sec. 4.2).\n";
}

prep::cli::RegisterInfoSection graph_info({"graph", 20, graph_section, print_graph});
prep::cli::RegisterInfoSection targets_info({"targets", 30, targets_section, print_targets});

}  // namespace
