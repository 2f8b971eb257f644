#pragma once
// strata's subcommands: each registers its options on the CLI11 app and runs when chosen.
// One file per subcommand (stream_command.cpp, health_command.cpp, ...).
#include <CLI/CLI.hpp>
#include <functional>

namespace strata::client {

using Runner = std::function<int()>;

Runner add_stream_command(CLI::App& app);
Runner add_health_command(CLI::App& app);
Runner add_eval_command(CLI::App& app);
Runner add_loadtest_command(CLI::App& app);
Runner add_view_command(CLI::App& app);

}  // namespace strata::client
