#include "eval_method.h"

#include <sstream>
#include <stdexcept>

namespace strata::client {

EvalMethod parse_eval_method(const std::string& entry, const RestirFlags& common) {
  EvalMethod m{"", common};
  std::stringstream parts(entry);
  std::getline(parts, m.method, ':');
  if (m.method.empty()) throw std::runtime_error("--methods: '" + entry + "' names no method before its flags");
  std::string line;  // the entry's flags as a command line, parsed by the same definitions as the common ones
  for (std::string flag; std::getline(parts, flag, ':');) {
    const size_t eq = flag.find('=');
    std::string name = flag.substr(0, eq);
    while (!name.empty() && name.front() == '-') name.erase(name.begin());
    if (name.empty()) throw std::runtime_error("--methods: '" + entry + "' has an empty flag (NAME[:FLAG=VALUE]...)");
    line += " --" + name;
    if (eq != std::string::npos) line += " " + flag.substr(eq + 1);
  }
  if (line.empty()) return m;
  CLI::App parser("the flags of one --methods entry");
  add_restir_flags(&parser, m.restir, /*eval=*/true);
  try {
    parser.parse(line, false);
  } catch (const CLI::ParseError& e) {
    throw std::runtime_error("--methods: '" + entry + "': " + e.what());
  }
  return m;
}

}  // namespace strata::client
