// strata: the client of the strata render service (stratad serve).
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <map>

#include "commands.h"

int main(int argc, char** argv) {
  CLI::App app{"strata: client of the strata render service (stratad serve)"};
  app.require_subcommand(1);
  std::map<CLI::App*, strata::client::Runner> runners;
  auto add = [&](strata::client::Runner (*adder)(CLI::App&)) {
    size_t before = app.get_subcommands({}).size();
    auto runner = adder(app);
    runners[app.get_subcommands({}).at(before)] = std::move(runner);
  };
  add(&strata::client::add_stream_command);
  add(&strata::client::add_health_command);
  add(&strata::client::add_eval_command);
  add(&strata::client::add_loadtest_command);
  add(&strata::client::add_view_command);
  CLI11_PARSE(app, argc, argv);
  try {
    for (auto* sub : app.get_subcommands()) return runners.at(sub)();
  } catch (const std::exception& e) {
    std::cerr << "strata: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
