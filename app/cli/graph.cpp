// prep graph: build the hierarchical motion graph (Sec. 4.1) of a motion set and write it for Graphviz.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "app/cli/command.h"
#include "engine/graph/motion_graph.h"
#include "engine/library/builtin.h"
#include "engine/util/files.h"

namespace {

prep::cli::RegisterCommand graph_command(
    "graph",
    "Build the motion graph of a motion set (core locomotion nodes, target motions hanging off them) and "
    "write it as Graphviz DOT",
    20, [](CLI::App& app) {
      struct Options {
        std::string motions, params, dot;
      };
      auto o = std::make_shared<Options>();
      app.add_option("--motions", o->motions, "Motion-set manifest (JSON); default: the built-in library");
      app.add_option("--params", o->params, "Params JSON file (default: the built-in defaults)");
      app.add_option("--dot", o->dot, "Write the graph here as Graphviz DOT (render: dot -Tsvg FILE -o graph.svg)")->required();
      app.callback([o] {
        const prep::Params params = o->params.empty() ? prep::Params{} : prep::load_params(o->params);
        const prep::MotionSet set = o->motions.empty() ? prep::make_builtin_motion_set(params) : prep::load_motion_set(o->motions, params);
        const prep::MotionGraph graph = prep::MotionGraph::build(set, params.graph);
        prep::write_file_atomic(o->dot, graph.to_dot());
        int core = 0;
        for (const prep::GraphNode& n : graph.nodes()) core += n.core ? 1 : 0;
        std::printf("%s: %zu nodes (%d core), %zu edges, built in %.1f ms; wrote %s\n", set.name.c_str(), graph.nodes().size(),
                    core, graph.edges().size(), 1000.0 * graph.build_seconds(), o->dot.c_str());
      });
    });

}  // namespace
