#pragma once
// The option table: every option of a session (RenderOptions in proto/strata/v1/render.proto) and
// of `stratad render` is one row here, and everything that depends on the list of options reads the
// rows: validation (the field and the limit in the error), defaults, the effective options, the
// renderer's RestirOptions, what a change in a FrameInput does, the session's decisions (whether
// the option applies to the method), the command-line flags of `stratad render` and `strata
// stream/eval/loadtest`, and docs/OPTIONS.md (`stratad options --markdown`). docs/ARCHITECTURE.md, "Options".
//
// A row names its proto field (RenderOptions.<name>, or RenderOptions.experimental.<name> for the
// paper-validation ablations), and the RestirOptions member it sets; a member's default is its
// initializer in render/restir/restir_options.h. Values travel as double between the proto, the
// table and RestirOptions: every option is a uint32, a float, a bool or an enum, all exact in a double.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "render/method_table.h"
#include "render/restir/restir_options.h"

namespace strata::options {

enum class Kind : uint8_t { count, real, flag, choice };  // uint32, float, bool, enum

// user: what a user of the service sets; experimental: the papers' validation variants and
// ablations (RenderOptions.experimental; flags listed by --help-experimental).
enum class Group : uint8_t { user, experimental };

// The methods an option applies to, by what the method table says of them (render::MethodSpec).
enum class Scope : uint8_t {
  every,           // every method
  reuse,           // the restir-* methods (MethodSpec::reuse)
  splatting,       // restir-splat, restir-splat-backup, restir-multilayer (MethodSpec::splatting)
  layers,          // restir-multilayer (MethodSpec::layers)
  fixed_primary,   // restir-gather, restir-di (MethodSpec::fixed_primary)
  colour_cv,       // restir-gather, restir-di, restir-splat, restir-splat-backup (RestirOptions::colour_cv_used)
};

// What a change of the option in a FrameInput does, for a method it applies to (for the others the
// change is kept and reported as not applying).
enum class OnChange : uint8_t {
  recreate,  // the GPU state is re-created with it from that frame on; history resets, Frame.history_reset_reason names it
  in_place,  // takes effect from that frame on without touching the GPU state (Frame.option_changes says so)
};

// Where the default of a row comes from.
enum class DefaultFrom : uint8_t {
  member,          // the RestirOptions member's initializer (or OptionSpec::fixed_default without a member)
  method,          // the method's (MethodSpec::confidence_cap): RestirOptions{}.moving_cap(method)
  image_height,    // RestirOptions::default_spatial_radius(height)
  service_limit,   // fixed_default, at most the service's limit (max_depth)
};

struct Choice {
  const char* name;   // as flags and decisions write it
  int proto;          // the value of the proto enum (RenderOptions' field)
  uint32_t value;     // the RestirOptions enum's value: the passes' constant
  const char* help;
};

struct OptionSpec {
  const char* name;                        // the proto field's name
  Group group = Group::user;
  Kind kind = Kind::count;
  Scope scope = Scope::reuse;
  OnChange on_change = OnChange::recreate;
  double lo = 0.0, hi = 0.0;               // the range of count and real options
  const char* zero = nullptr;              // what 0 means where it is special ("off"), allowed even below lo
  const char* limit = nullptr;             // the named limit of hi: a restir_limits.h constant, or a service limit ("max_spp")
  const char* unit = nullptr;              // "pixels", "stops", ...
  DefaultFrom default_from = DefaultFrom::member;
  double fixed_default = 0.0;              // the default of rows without a RestirOptions member
  const char* default_text = nullptr;      // the default as docs and help say it where it is not a plain value
  std::span<const Choice> choices = {};
  const char* flag = nullptr;              // the command-line flag ("--spatial-neighbors")
  bool negated_flag = false;               // kind flag: `flag` takes no value and sets false ("--no-temporal")
  const char* help = "";                   // what it does
  const char* sets = "";                   // what it sets on the device
  // The RestirOptions member; nullptr for the options the renderer's settings or the service hold
  // (spp, max_depth, exposure).
  double (*get)(const render::RestirOptions&) = nullptr;
  void (*set)(render::RestirOptions&, double) = nullptr;
  // What RestirOptions' 0 means where it may hold 0 outside [lo, hi] (its automatic value; the proto
  // holds the value in effect).
  const char* restir_zero = nullptr;
};

std::span<const OptionSpec> option_table();
// The row of `name`; nullptr when there is none.
const OptionSpec* find_option(std::string_view name);

// Whether the row applies to `method` (its Scope); and, when not, why, as a decision says it.
bool applies(const OptionSpec& o, const render::MethodSpec& method);
std::string scope_text(Scope s);
std::string not_applying_reason(const OptionSpec& o, const render::MethodSpec& method);

// The default value of a row (DefaultFrom::member and service_limit with its fixed default).
double default_value(const OptionSpec& o);
// A value as flags, decisions and docs write it: "3", "0.6", "true", "hybrid".
std::string value_text(const OptionSpec& o, double v);
// The name of a RestirOptions choice as the table writes it: choice_name("shift", o.shift) is "hybrid".
template <class E>
std::string choice_name(std::string_view option, E value) {
  return value_text(*find_option(option), double(static_cast<uint32_t>(value)));
}
// Sets RestirOptions' choice `option` to the one called `name` ("uniform"): std::invalid_argument when there is none.
void set_choice(render::RestirOptions& o, std::string_view option, const std::string& name);
// The value of a flag's text; std::nullopt when it is not one of the row's values (kind and choices; not the range).
std::optional<double> parse_value(const OptionSpec& o, const std::string& text);
const Choice* find_choice(const OptionSpec& o, double proto_or_value, bool by_proto);
// "[lo, hi]" or "one of a, b, c" with the meaning of 0, for help and docs.
std::string range_text(const OptionSpec& o, double hi_override = 0.0);
// The range check of one value: an error message naming `field` and the limit, or empty.
std::string range_error(const OptionSpec& o, double v, const std::string& field, double hi_override = 0.0, bool restir = false);

}  // namespace strata::options
