#pragma once
// The option table as command-line flags, for `stratad render` and `strata stream/eval/loadtest`:
// one flag per row, its help, range and default from the row, so that the commands cannot disagree.
// The user group is listed by --help; the experimental group is hidden there and listed by
// --help-experimental. A flag is sent (set in RenderOptions) only when given, so that the server's
// defaults apply otherwise.
#include <initializer_list>
#include <map>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

#include "options/option_table.h"
#include "strata/v1/render.pb.h"

namespace strata::options {

// The options given on a command line: option name -> its value as text ("3", "hybrid", "false").
struct OptionFlags {
  std::map<std::string, std::string> given;
};

// Adds a flag for every row of the table but those named in `except` (options the command defines
// itself: spp, max_depth and exposure, whose meaning there differs) and --help-experimental.
void add_option_flags(CLI::App* cmd, OptionFlags& flags, std::initializer_list<std::string_view> except);

// The help line of a row's flag: what it does, the methods, the range and the default.
std::string flag_help(const OptionSpec& o);

// The given flags as they are written on a command line, in table order ("" when none is given).
std::string option_flags_text(const OptionFlags& flags);

// Sets the given options in `o`; std::runtime_error naming the flag whose value is not one of the option's.
void set_options(const OptionFlags& flags, strata::v1::RenderOptions& o);
// The same for the renderer's options (`stratad render`, which renders in-process).
void set_options(const OptionFlags& flags, render::RestirOptions& o);

}  // namespace strata::options
