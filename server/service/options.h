#pragma once
// Methods and their options (docs/ARCHITECTURE.md, Methods and Options): which exist, which are
// available, defaults, range checks, and the choices a session makes from them and from its scene.
// Every function here walks the option table (options/option_table.h): no option is named but where
// its meaning needs it (the method-dependent defaults, the decisions' reasons).
#include <optional>
#include <string>
#include <vector>

#include "render/method_table.h"
#include "options/option_table.h"
#include "render/restir/restir_options.h"
#include "render/restir/layer_count.h"
#include "service/config.h"
#include "strata/v1/render.pb.h"

namespace strata::service {

namespace v1 = ::strata::v1;

// Whether the client asked for `method auto` (service/method_auto.h): by name, or by naming none.
bool is_auto_method(const std::string& requested);
// The method table's row (render/method_table.h) of a requested method; for auto (empty or "auto")
// restir-gather's, the row whose options auto's calibration runs with. An unknown method is
// INVALID_ARGUMENT naming the methods there are.
const render::MethodSpec& check_method(const std::string& requested, const std::string& field);

// Range checks of the fields that are set (the table's ranges; spp and max_depth: the service's
// limits); `field` prefixes the names ("options"). INVALID_ARGUMENT naming the field and the limit.
void check_options(const v1::RenderOptions& o, const ServiceLimits& limits, const std::string& field);
// What `method` requires of the fields that are set (the restir-* methods render spp = 1); `field`
// prefixes the names. `auto_method`: the session's method is auto, which may choose `method` (the
// message then says so).
void check_method_options(const render::MethodSpec& method, const v1::RenderOptions& o, const std::string& field,
                          bool auto_method = false);
// DOMAIN_MAP needs a method with pixel layers (restir-multilayer): INVALID_ARGUMENT otherwise.
void check_method_encodings(const render::MethodSpec& method, const std::vector<v1::ImageEncoding>& encodings,
                            const std::string& field);
// Every field set: the requested value, else the table's default (max_depth at most limits.max_depth;
// spatial_radius from the image `height`, render::RestirOptions::default_spatial_radius; confidence_cap
// the `method`'s).
v1::RenderOptions with_defaults(const v1::RenderOptions& requested, const render::MethodSpec& method, const ServiceLimits& limits,
                                uint32_t height);
// Enum fields set to UNSPECIFIED take their defaults.
void normalize(v1::RenderOptions& o);

// The renderer's ReSTIR options from effective options (every field set).
render::RestirOptions restir_options(const v1::RenderOptions& effective);

// One option that a FrameInput changed: its values before and after (the effective options' text)
// and whether it applies to the session's method (options::applies).
struct OptionChange {
  const options::OptionSpec* option;
  std::string from, to;
  bool applies;
};
// The options whose effective values differ between `before` and `after`, in table order.
std::vector<OptionChange> option_changes(const render::MethodSpec& method, const v1::RenderOptions& before,
                                         const v1::RenderOptions& after);
// The value of option `name` in effective options, as decisions write it ("hybrid", "3", "true").
std::string option_text(const v1::RenderOptions& o, const char* name);

// What was enabled and why, from the method (`requested_method`: as the client named it, empty for
// the default), the options and the scene; `measured_layers`: what `layers auto` measured on the
// scene's first frame (render::measure_layers), when the method has layers and auto was asked.
std::vector<v1::Decision> decide(const render::MethodSpec& method, const std::string& requested_method,
                                 const v1::RenderOptions& requested,
                                 const v1::RenderOptions& effective, const std::vector<v1::ImageEncoding>& encodings,
                                 const v1::SceneAnalysis& scene, const std::optional<render::LayerCount>& measured_layers = {});

}  // namespace strata::service
