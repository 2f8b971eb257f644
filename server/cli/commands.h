#pragma once
// stratad's subcommands; each registers its options on the CLI11 app and runs when chosen.
#include <CLI/CLI.hpp>
#include <functional>

namespace strata::cli {

using Runner = std::function<int()>;

Runner add_render_command(CLI::App& app);
Runner add_export_scene_command(CLI::App& app);
Runner add_list_scenes_command(CLI::App& app);
Runner add_bench_command(CLI::App& app);
Runner add_serve_command(CLI::App& app);
Runner add_options_command(CLI::App& app);

}  // namespace strata::cli
