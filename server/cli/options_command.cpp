// `stratad options`: the option table (docs/ARCHITECTURE.md, Options), one line per option; with
// --markdown, docs/OPTIONS.md as it is checked in.
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "options/option_docs.h"
#include "options/option_flags.h"
#include "options/option_proto.h"

namespace strata::cli {

Runner add_options_command(CLI::App& app) {
  auto markdown = std::make_shared<bool>(false);
  auto* cmd = app.add_subcommand("options", "list the session options (RenderOptions) and their flags");
  cmd->add_flag("--markdown", *markdown, "write docs/OPTIONS.md (generated from the option table)");
  return [markdown] {
    if (*markdown) {
      std::cout << options::options_markdown();
      return 0;
    }
    for (const auto& o : options::option_table())
      std::cout << options::field_path(o, "RenderOptions") << "  " << o.flag << "\n    " << options::flag_help(o) << "\n";
    return 0;
  };
}

}  // namespace strata::cli
