// stratad: the strata render daemon and its offline tools.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <map>

#include "cli/commands.h"

int main(int argc, char** argv) {
  CLI::App app{"stratad: real-time path-tracing render service (ReSTIR on Vulkan ray queries)"};
  app.require_subcommand(1);
  std::map<CLI::App*, strata::cli::Runner> runners;
  auto add = [&](strata::cli::Runner (*adder)(CLI::App&)) {
    size_t before = app.get_subcommands({}).size();
    auto runner = adder(app);
    runners[app.get_subcommands({}).at(before)] = std::move(runner);
  };
  add(&strata::cli::add_render_command);
  add(&strata::cli::add_export_scene_command);
  add(&strata::cli::add_list_scenes_command);
  add(&strata::cli::add_bench_command);
  add(&strata::cli::add_serve_command);
  add(&strata::cli::add_options_command);
  CLI11_PARSE(app, argc, argv);
  try {
    for (auto* sub : app.get_subcommands()) return runners.at(sub)();
  } catch (const std::exception& e) {
    std::cerr << "stratad: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
