#pragma once
// Methods and their options (docs/ARCHITECTURE.md, Methods): which exist, which are available, defaults,
// range checks, and the choices a session makes from them and from its scene.
#include <optional>
#include <string>
#include <vector>

#include "render/method_table.h"
#include "render/renderer.h"
#include "render/restir/layer_count.h"
#include "service/config.h"
#include "strata/v1/render.pb.h"

namespace strata::service {

namespace v1 = ::strata::v1;

// The method table's row (render/method_table.h) of a requested method; empty means the default
// method. An unknown method is INVALID_ARGUMENT naming the methods there are.
const render::MethodSpec& check_method(const std::string& requested, const std::string& field);

// Range checks of the fields that are set; `field` prefixes the names ("options").
void check_options(const v1::RenderOptions& o, const ServiceLimits& limits, const std::string& field);
// What `method` requires of the fields that are set (the restir-* methods render spp = 1); `field`
// prefixes the names. `defaulted`: the client named no method (the message then says which it got).
void check_method_options(const render::MethodSpec& method, const v1::RenderOptions& o, const std::string& field,
                          bool defaulted = false);
// DOMAIN_MAP needs a method with pixel layers (restir-multilayer): INVALID_ARGUMENT otherwise.
void check_method_encodings(const render::MethodSpec& method, const std::vector<v1::ImageEncoding>& encodings,
                            const std::string& field);
// Every field set: the requested value, else the default (max_depth at most limits.max_depth;
// spatial_radius from the image `height`, render::RestirOptions::default_spatial_radius; confidence_cap
// the `method`'s).
v1::RenderOptions with_defaults(const v1::RenderOptions& requested, const render::MethodSpec& method, const ServiceLimits& limits,
                                uint32_t height);
// Enum fields set to UNSPECIFIED take their defaults.
void normalize(v1::RenderOptions& o);

// The renderer's ReSTIR options from effective options (every field set).
render::RestirOptions restir_options(const v1::RenderOptions& effective);

std::string shift_name(v1::Shift s);
std::string suffix_name(v1::Suffix s);
std::string mis_name(v1::Mis m);
std::string layer_mode_name(v1::LayerMode m);
std::string lod_vertices_name(v1::LodVertices v);
std::string lod_mapping_name(v1::LodMapping m);

// What was enabled and why, from the method (`requested_method`: as the client named it, empty for
// the default), the options and the scene; `measured_layers`: what `layers auto` measured on the
// scene's first frame (render::measure_layers), when the method has layers and auto was asked.
std::vector<v1::Decision> decide(const render::MethodSpec& method, const std::string& requested_method,
                                 const v1::RenderOptions& requested,
                                 const v1::RenderOptions& effective, const std::vector<v1::ImageEncoding>& encodings,
                                 const v1::SceneAnalysis& scene, const std::optional<render::LayerCount>& measured_layers = {});

}  // namespace strata::service
