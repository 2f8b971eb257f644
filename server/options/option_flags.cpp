#include "options/option_flags.h"

#include <algorithm>
#include <iostream>
#include <stdexcept>

#include "options/option_proto.h"

namespace strata::options {
namespace {

std::string default_help(const OptionSpec& o) {
  if (o.default_text) return o.default_text;
  return value_text(o, default_value(o));
}

// The flag's value check: the row's kind and choices, and its range where the table holds it
// (spp and max_depth are held to the server's limits, which the client does not know).
std::string check_text(const OptionSpec& o, const std::string& text) {
  const std::optional<double> v = parse_value(o, text);
  if (!v) return std::string(o.flag) + ": '" + text + "' is not " + (o.kind == Kind::count ? "a count: " : "one of: ") + range_text(o);
  if (o.hi == 0.0 && o.limit) return "";
  const std::string error = range_error(o, *v, o.flag);
  return error;
}

void print_experimental(const CLI::App* cmd, std::ostream& out) {
  out << "Experimental flags of " << cmd->get_name()
      << ": the papers' validation variants and ablations (RenderOptions.experimental; docs/OPTIONS.md):\n";
  for (const auto& o : option_table()) {
    if (o.group != Group::experimental) continue;
    std::string name = o.flag;
    if (!o.negated_flag) name += o.kind == Kind::choice || o.kind == Kind::flag ? " " + range_text(o) : " VALUE";
    out << "  " << name << "\n      " << flag_help(o) << "\n";
  }
}

}  // namespace

std::string flag_help(const OptionSpec& o) {
  std::string s = o.help;
  s += " [" + scope_text(o.scope) + "]";
  if (o.negated_flag) return "turns off: " + s + " (" + o.name + " = false)";
  s += " (" + range_text(o) + "; default " + default_help(o) + ")";
  return s;
}

void add_option_flags(CLI::App* cmd, OptionFlags& flags, std::initializer_list<std::string_view> except) {
  for (const auto& row : option_table()) {
    if (std::find(except.begin(), except.end(), std::string_view(row.name)) != except.end()) continue;
    const OptionSpec* o = &row;
    CLI::Option* opt = nullptr;
    if (o->negated_flag) {
      opt = cmd->add_flag_callback(o->flag, [&flags, o] { flags.given[o->name] = "false"; }, flag_help(*o));
    } else {
      opt = cmd->add_option_function<std::string>(
          o->flag, [&flags, o](const std::string& text) { flags.given[o->name] = text; }, flag_help(*o));
      opt->check(CLI::Validator([o](std::string& text) { return check_text(*o, text); }, ""));
      opt->type_name(o->kind == Kind::count ? "UINT" : o->kind == Kind::real ? "FLOAT" : o->kind == Kind::flag ? "BOOL" : "CHOICE");
    }
    // An empty group hides the flag from --help; --help-experimental lists it.
    if (o->group == Group::experimental) opt->group("");
  }
  cmd->add_flag_callback(
      "--help-experimental",
      [cmd] {
        print_experimental(cmd, std::cout);
        throw CLI::Success();
      },
      "list the experimental flags (the papers' validation variants and ablations) and exit");
}

std::string option_flags_text(const OptionFlags& flags) {
  std::string s;
  for (const auto& o : option_table()) {
    auto it = flags.given.find(o.name);
    if (it == flags.given.end()) continue;
    s += (s.empty() ? "" : " ") + std::string(o.flag) + (o.negated_flag ? "" : " " + it->second);
  }
  return s;
}

template <class Set>
void for_each_given(const OptionFlags& flags, Set set) {
  for (const auto& [name, text] : flags.given) {
    const OptionSpec* o = find_option(name);
    if (!o) throw std::runtime_error("'" + name + "' is not an option");
    const std::optional<double> v = parse_value(*o, text);
    if (!v) throw std::runtime_error(std::string(o->flag) + ": '" + text + "' is not one of: " + range_text(*o));
    set(*o, *v);
  }
}

void set_options(const OptionFlags& flags, v1::RenderOptions& out) {
  for_each_given(flags, [&](const OptionSpec& o, double v) { set_value(out, o, v); });
}

void set_options(const OptionFlags& flags, render::RestirOptions& out) {
  for_each_given(flags, [&](const OptionSpec& o, double v) {
    if (!o.set) throw std::runtime_error(std::string(o.flag) + " is not an option of the renderer's RestirOptions");
    o.set(out, v);
  });
}

}  // namespace strata::options
