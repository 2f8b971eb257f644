#pragma once
// The session options as command-line flags of strata stream, eval and loadtest: the option table's
// flags (server/options/option_flags.h), each sent only when given, so that the server's defaults
// apply otherwise. The commands define spp, max_depth and exposure themselves (their meaning
// differs: eval's spp is per method, at equal time), and eval its --splats-per-frame.
#include "options/option_flags.h"

namespace strata::client {

using RestirFlags = options::OptionFlags;

// Adds the table's flags but those the command defines itself (`eval`: --splats-per-frame too) and
// --help-experimental.
inline void add_restir_flags(CLI::App* cmd, RestirFlags& r, bool eval = false) {
  if (eval) options::add_option_flags(cmd, r, {"spp", "max_depth", "exposure", "splats_per_frame"});
  else options::add_option_flags(cmd, r, {"spp", "max_depth", "exposure"});
}

// The given flags as they are written on a command line ("" when none is given).
inline std::string restir_flags_text(const RestirFlags& r) { return options::option_flags_text(r); }

// Sets the given flags in `o`; throws std::runtime_error naming a flag whose value is not allowed.
inline void set_restir_options(const RestirFlags& r, strata::v1::RenderOptions& o) { options::set_options(r, o); }

}  // namespace strata::client
