#pragma once
// Methods and their options (DESIGN.md section 2): which exist, which are available, defaults,
// range checks, and the choices a session makes from them and from its scene.
#include <string>
#include <vector>

#include "render/renderer.h"
#include "service/config.h"
#include "strata/v1/render.pb.h"

namespace strata::service {

namespace v1 = ::strata::v1;

// What a method does, as far as its options are concerned.
struct MethodTraits {
  const char* name;
  bool reuse;      // resampling (ReSTIR): initial, temporal, spatial passes
  bool splatting;  // forward projection of reservoirs (splats_per_frame)
  bool layers;     // pixel-layer domains
};

// Every method of DESIGN.md section 2, available or not.
const std::vector<MethodTraits>& known_methods();
// Empty means pt. Unknown and not-yet-available methods are INVALID_ARGUMENT naming what is available.
const MethodTraits& check_method(const std::string& requested, const std::string& field);

// Range checks of the fields that are set; `field` prefixes the names ("options").
void check_options(const v1::RenderOptions& o, const ServiceLimits& limits, const std::string& field);
// What `method` requires of the fields that are set (the restir-* methods render spp = 1); `field`
// prefixes the names.
void check_method_options(const MethodTraits& method, const v1::RenderOptions& o, const std::string& field);
// Every field set: the requested value, else the default (max_depth at most limits.max_depth).
v1::RenderOptions with_defaults(const v1::RenderOptions& requested, const ServiceLimits& limits);
// Enum fields set to UNSPECIFIED take their defaults.
void normalize(v1::RenderOptions& o);

// The renderer's ReSTIR options from effective options (every field set).
render::RestirOptions restir_options(const v1::RenderOptions& effective);

std::string shift_name(v1::Shift s);
std::string mis_name(v1::Mis m);
std::string lod_mapping_name(v1::LodMapping m);

// What was enabled and why, from the method, the options and the scene.
std::vector<v1::Decision> decide(const MethodTraits& method, const v1::RenderOptions& requested,
                                 const v1::RenderOptions& effective, const std::vector<v1::ImageEncoding>& encodings,
                                 const v1::SceneAnalysis& scene);

}  // namespace strata::service
