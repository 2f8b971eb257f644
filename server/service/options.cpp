#include "service/options.h"

#include <algorithm>
#include <cmath>

#include "options/option_proto.h"
#include "render/method_table.h"
#include "service/errors.h"
#include "service/method_auto.h"

namespace strata::service {
namespace {

// The service's limit of a row whose upper bound is one (spp, max_depth); 0: the table's.
double service_limit(const options::OptionSpec& o, const ServiceLimits& limits) {
  if (!o.limit) return 0.0;
  const std::string limit = o.limit;
  if (limit == "max_spp") return limits.max_spp;
  if (limit == "max_depth") return limits.max_depth;
  return 0.0;
}

// The proto enum's names but UNSPECIFIED: "SHIFT_RECONNECTION, SHIFT_HYBRID".
std::string enum_names(const options::OptionSpec& o) {
  std::string s;
  const auto* e = options::proto_field(o)->enum_type();
  for (int i = 0; i < e->value_count(); ++i)
    if (e->value(i)->number() != 0) s += (s.empty() ? "" : ", ") + std::string(e->value(i)->name());
  return s;
}

}  // namespace

bool is_auto_method(const std::string& requested) { return requested.empty() || requested == k_auto_method; }

const render::MethodSpec& check_method(const std::string& requested, const std::string& field) {
  // auto calibrates with restir-gather's row: its options and what it requires of them.
  const std::string name = is_auto_method(requested) ? k_auto_reuse : requested;
  for (const auto& m : render::method_table())
    if (name == m.name) return m;
  fail_invalid(field + " = '" + name + "' is not a method; methods: " + std::string(k_auto_method) + ", " +
               render::method_names());
}

void check_options(const v1::RenderOptions& o, const ServiceLimits& limits, const std::string& field) {
  for (const auto& row : options::option_table()) {
    if (!options::has_value(o, row)) continue;
    const std::string name = options::field_path(row, field);
    if (row.kind == options::Kind::choice) {
      const int n = options::proto_number(o, row);
      if (n != 0 && !options::find_choice(row, n, /*by_proto=*/true))
        fail_invalid(name + " = " + std::to_string(n) + " is not one of " + enum_names(row));
      continue;
    }
    const std::string error = options::range_error(row, options::get_value(o, row), name, service_limit(row, limits));
    if (!error.empty()) fail_invalid(error);
  }
}

void check_method_encodings(const render::MethodSpec& method, const std::vector<v1::ImageEncoding>& encodings,
                            const std::string& field) {
  for (size_t i = 0; i < encodings.size(); ++i)
    if (encodings[i] == v1::IMAGE_ENCODING_DOMAIN_MAP && !method.layers)
      fail_invalid(field + "[" + std::to_string(i) + "] = DOMAIN_MAP but method " + method.name +
                   " has one domain per pixel: the domain map needs pixel layers (method restir-multilayer)");
}

void check_method_options(const render::MethodSpec& method, const v1::RenderOptions& o, const std::string& field,
                          bool auto_method) {
  if (method.reuse && o.has_spp() && o.spp() != 1)
    fail_invalid(field + ".spp = " + std::to_string(o.spp()) + " but method " +
                 (auto_method ? std::string(k_auto_method) + " (the default when no method is named) may choose " : "") +
                 method.name + (auto_method ? ", which" : "") +
                 " keeps one reservoir per pixel and renders 1 sample per pixel per frame (spp must be 1); use " + field +
                 ".initial_candidates for more candidates per frame" +
                 (auto_method ? ", or method = \"pt\" for several path-traced samples per pixel" : ""));
}

render::RestirOptions restir_options(const v1::RenderOptions& e) {
  render::RestirOptions r;
  for (const auto& row : options::option_table())
    if (row.set) row.set(r, options::get_value(e, row));
  return r;
}

void normalize(v1::RenderOptions& o) {
  for (const auto& row : options::option_table())
    if (row.kind == options::Kind::choice && options::has_value(o, row) && options::proto_number(o, row) == 0)
      options::set_value(o, row, options::default_value(row));
}

v1::RenderOptions with_defaults(const v1::RenderOptions& requested, const render::MethodSpec& method, const ServiceLimits& limits,
                                uint32_t height) {
  v1::RenderOptions o;
  const render::RestirOptions restir;
  for (const auto& row : options::option_table()) {
    double v = options::default_value(row);
    switch (row.default_from) {
      case options::DefaultFrom::member: break;
      case options::DefaultFrom::method: v = restir.moving_cap(method); break;
      case options::DefaultFrom::image_height: v = render::RestirOptions::default_spatial_radius(height); break;
      case options::DefaultFrom::service_limit: v = std::min(v, service_limit(row, limits)); break;
    }
    options::set_value(o, row, v);
  }
  o.MergeFrom(requested);  // proto3 optional: only fields that are set overwrite
  normalize(o);
  return o;
}

std::vector<OptionChange> option_changes(const render::MethodSpec& method, const v1::RenderOptions& before,
                                         const v1::RenderOptions& after) {
  std::vector<OptionChange> out;
  for (const auto& row : options::option_table()) {
    const std::string from = options::value_text(row, options::get_value(before, row));
    const std::string to = options::value_text(row, options::get_value(after, row));
    if (from != to) out.push_back({&row, from, to, options::applies(row, method)});
  }
  return out;
}

std::string option_text(const v1::RenderOptions& o, const char* name) {
  const options::OptionSpec* row = options::find_option(name);
  return row ? options::value_text(*row, options::get_value(o, *row)) : std::string();
}

}  // namespace strata::service
