#include "service/options.h"

#include <algorithm>
#include <cmath>

#include "render/method_table.h"
#include "render/renderer.h"
#include "restir/layer_data.h"
#include "restir/restir_limits.h"
#include "service/errors.h"
#include "service/input_checks.h"

namespace strata::service {
namespace {

void check_range(bool has, uint64_t v, uint64_t lo, uint64_t hi, const std::string& field, const std::string& limit = "") {
  if (has && (v < lo || v > hi))
    fail_invalid(field + " = " + std::to_string(v) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]" +
                 (limit.empty() ? "" : " (" + limit + ")"));
}

void check_float(bool has, float v, float lo, float hi, const std::string& field, const std::string& unit = "") {
  if (has && (!std::isfinite(v) || v < lo || v > hi))
    fail_invalid(field + " = " + format_float(v) + " is outside [" + format_float(lo) + ", " + format_float(hi) + "]" +
                 (unit.empty() ? "" : " " + unit));
}

void check_enum(bool has, int v, bool (*valid)(int), const std::string& field, const std::string& names) {
  if (has && !valid(v)) fail_invalid(field + " = " + std::to_string(v) + " is not one of " + names);
}

}  // namespace

const render::MethodSpec& check_method(const std::string& requested, const std::string& field) {
  const std::string name = requested.empty() ? render::k_default_method : requested;
  for (const auto& m : render::method_table())
    if (name == m.name) return m;
  fail_invalid(field + " = '" + name + "' is not a method; methods: " + render::method_names());
}

void check_options(const v1::RenderOptions& o, const ServiceLimits& limits, const std::string& field) {
  const std::string p = field + ".";
  check_range(o.has_spp(), o.spp(), 1, limits.max_spp, p + "spp", "max_spp");
  check_range(o.has_max_depth(), o.max_depth(), 1, limits.max_depth, p + "max_depth", "max_depth");
  check_enum(o.has_shift(), o.shift(), &v1::Shift_IsValid, p + "shift", "SHIFT_RECONNECTION, SHIFT_HYBRID");
  check_enum(o.has_mis(), o.mis(), &v1::Mis_IsValid, p + "mis", "MIS_BALANCE, MIS_PAIRWISE");
  check_enum(o.has_suffix(), o.suffix(), &v1::Suffix_IsValid, p + "suffix", "SUFFIX_AUTO, SUFFIX_REPLAY, SUFFIX_CACHED, SUFFIX_FAIL");
  check_enum(o.has_lod_mapping(), o.lod_mapping(), &v1::LodMapping_IsValid, p + "lod_mapping",
                             "LOD_MAPPING_AUTO, LOD_MAPPING_OFF, LOD_MAPPING_UV");
  check_range(o.has_layers(), o.layers(), 0, gpu::LAYERS_MAX, p + "layers", "0 = auto");
  check_range(o.has_hole_fill_radius(), o.hole_fill_radius(), 0, gpu::RESTIR_MAX_HOLE_FILL_RADIUS, p + "hole_fill_radius", "0 = off");
  check_range(o.has_silhouette_band(), o.silhouette_band(), 0, gpu::RESTIR_MAX_SILHOUETTE_BAND, p + "silhouette_band", "0 = off");
  check_range(o.has_reveal_lookahead(), o.reveal_lookahead(), 0, gpu::RESTIR_MAX_REVEAL_LOOKAHEAD, p + "reveal_lookahead", "0 = off");
  check_enum(o.has_lod_vertices(), o.lod_vertices(), &v1::LodVertices_IsValid, p + "lod_vertices",
             "LOD_VERTICES_BOTH, LOD_VERTICES_PRIMARY, LOD_VERTICES_RECONNECTION");
  check_enum(o.has_layer_mode(), o.layer_mode(), &v1::LayerMode_IsValid, p + "layer_mode",
             "LAYER_MODE_ACTIVE, LAYER_MODE_UNIFORM, LAYER_MODE_NO_DEPTH_RANGES");
  // The ranges of shaders/restir/restir_limits.h, which render::RestirOptions::validate checks too.
  using namespace gpu;
  check_float(o.has_confidence_cap(), o.confidence_cap(), RESTIR_MIN_CONFIDENCE_CAP, RESTIR_MAX_CONFIDENCE_CAP, p + "confidence_cap");
  if (o.has_still_confidence_cap() && o.still_confidence_cap() != 0.0f)
    check_float(true, o.still_confidence_cap(), RESTIR_MIN_CONFIDENCE_CAP, RESTIR_MAX_CONFIDENCE_CAP, p + "still_confidence_cap",
                "(0 = confidence_cap)");
  check_range(o.has_spatial_neighbors(), o.spatial_neighbors(), 0, RESTIR_MAX_SPATIAL_NEIGHBORS, p + "spatial_neighbors");
  check_float(o.has_spatial_radius(), o.spatial_radius(), RESTIR_MIN_SPATIAL_RADIUS, RESTIR_MAX_SPATIAL_RADIUS, p + "spatial_radius",
              "pixels");
  check_range(o.has_initial_candidates(), o.initial_candidates(), 1, RESTIR_MAX_INITIAL_CANDIDATES, p + "initial_candidates");
  check_range(o.has_light_candidates(), o.light_candidates(), 1, RESTIR_MAX_LIGHT_CANDIDATES, p + "light_candidates");
  check_range(o.has_splats_per_frame(), o.splats_per_frame(), 1, RESTIR_MAX_SPLATS_PER_FRAME, p + "splats_per_frame");
  check_range(o.has_disocclusion_spatial_neighbors(), o.disocclusion_spatial_neighbors(), 0, RESTIR_MAX_SPATIAL_NEIGHBORS,
              p + "disocclusion_spatial_neighbors", "0 = spatial_neighbors");
  check_range(o.has_disocclusion_initial_candidates(), o.disocclusion_initial_candidates(), 0, RESTIR_MAX_INITIAL_CANDIDATES,
              p + "disocclusion_initial_candidates", "0 = the method's");
  check_range(o.has_direct_strata(), o.direct_strata(), 1, RESTIR_MAX_DIRECT_STRATA, p + "direct_strata");
  check_range(o.has_albedo_strata(), o.albedo_strata(), 1, RESTIR_MAX_DIRECT_STRATA, p + "albedo_strata", "1 = off");
  check_float(o.has_colour_cv(), o.colour_cv(), 0.0f, 1.0f, p + "colour_cv", "(0 = off)");
  check_float(o.has_exposure(), o.exposure(), -64.0f, 64.0f, p + "exposure");
}

void check_method_encodings(const render::MethodSpec& method, const std::vector<v1::ImageEncoding>& encodings,
                            const std::string& field) {
  for (size_t i = 0; i < encodings.size(); ++i)
    if (encodings[i] == v1::IMAGE_ENCODING_DOMAIN_MAP && !method.layers)
      fail_invalid(field + "[" + std::to_string(i) + "] = DOMAIN_MAP but method " + method.name +
                   " has one domain per pixel: the domain map needs pixel layers (method restir-multilayer)");
}

void check_method_options(const render::MethodSpec& method, const v1::RenderOptions& o, const std::string& field,
                          bool defaulted) {
  if (method.reuse && o.has_spp() && o.spp() != 1)
    fail_invalid(field + ".spp = " + std::to_string(o.spp()) + " but method " + method.name +
                 (defaulted ? " (the default: no method was named)" : "") +
                 " keeps one reservoir per pixel and renders 1 sample per pixel per frame (spp must be 1); use " + field +
                 ".initial_candidates for more candidates per frame" +
                 (defaulted ? ", or method = \"pt\" for several path-traced samples per pixel" : ""));
}

render::RestirOptions restir_options(const v1::RenderOptions& e) {
  render::RestirOptions r;
  r.shift = shift_name(e.shift());
  r.mis = mis_name(e.mis());
  r.suffix = suffix_name(e.suffix());
  r.unbiased = e.unbiased();
  r.temporal = e.temporal_reuse();
  r.spatial = e.spatial_reuse();
  r.confidence_cap = e.confidence_cap();
  r.still_confidence_cap = e.still_confidence_cap();
  r.spatial_neighbors = e.spatial_neighbors();
  r.spatial_radius = e.spatial_radius();
  r.initial_candidates = e.initial_candidates();
  r.light_candidates = e.light_candidates();
  r.splats_per_frame = e.splats_per_frame();
  r.disocclusion_spatial_neighbors = e.disocclusion_spatial_neighbors();
  r.disocclusion_initial_candidates = e.disocclusion_initial_candidates();
  r.direct_strata = e.direct_strata();
  r.albedo_strata = e.albedo_strata();
  r.colour_cv = e.colour_cv();
  r.temporal_filter = e.temporal_filter();
  r.layers = e.layers();
  r.hole_fill_radius = e.hole_fill_radius();
  r.silhouette_band = e.silhouette_band();
  r.reveal_lookahead = e.reveal_lookahead();
  r.deep_backup = e.deep_backup();
  r.layer_mode = layer_mode_name(e.layer_mode());
  r.lod_mapping = lod_mapping_name(e.lod_mapping());
  r.lod_matching = e.lod_matching();
  r.lod_vertices = lod_vertices_name(e.lod_vertices());
  return r;
}

void normalize(v1::RenderOptions& o) {
  if (o.shift() == v1::SHIFT_UNSPECIFIED) o.set_shift(v1::SHIFT_HYBRID);
  if (o.mis() == v1::MIS_UNSPECIFIED) o.set_mis(v1::MIS_PAIRWISE);
  if (o.suffix() == v1::SUFFIX_UNSPECIFIED) o.set_suffix(v1::SUFFIX_AUTO);
  if (o.lod_mapping() == v1::LOD_MAPPING_UNSPECIFIED) o.set_lod_mapping(v1::LOD_MAPPING_AUTO);
  if (o.layer_mode() == v1::LAYER_MODE_UNSPECIFIED) o.set_layer_mode(v1::LAYER_MODE_ACTIVE);
  if (o.lod_vertices() == v1::LOD_VERTICES_UNSPECIFIED) o.set_lod_vertices(v1::LOD_VERTICES_BOTH);
}

v1::RenderOptions with_defaults(const v1::RenderOptions& requested, const render::MethodSpec& method, const ServiceLimits& limits,
                                uint32_t height) {
  v1::RenderOptions o;
  o.set_spp(1);
  o.set_max_depth(std::min<uint32_t>(16, limits.max_depth));
  o.set_shift(v1::SHIFT_HYBRID);
  o.set_mis(v1::MIS_PAIRWISE);
  o.set_suffix(v1::SUFFIX_AUTO);
  o.set_lod_mapping(v1::LOD_MAPPING_AUTO);
  // The ReSTIR defaults are render::RestirOptions' and the method's.
  const render::RestirOptions restir;
  o.set_confidence_cap(restir.moving_cap(method));
  o.set_still_confidence_cap(restir.still_confidence_cap);
  o.set_spatial_neighbors(restir.spatial_neighbors);
  o.set_spatial_radius(restir.spatial_radius_pixels(height));
  o.set_initial_candidates(restir.initial_candidates);
  o.set_light_candidates(restir.light_candidates);
  o.set_temporal_reuse(restir.temporal);
  o.set_spatial_reuse(restir.spatial);
  o.set_unbiased(restir.unbiased);
  o.set_disocclusion_spatial_neighbors(restir.disocclusion_spatial_neighbors);
  o.set_disocclusion_initial_candidates(restir.disocclusion_initial_candidates);  // 0: the method's (it needs k, not known here)
  o.set_direct_strata(restir.direct_strata);
  o.set_albedo_strata(restir.albedo_strata);
  o.set_colour_cv(restir.colour_cv);
  o.set_temporal_filter(restir.temporal_filter);
  o.set_layers(restir.layers);
  o.set_hole_fill_radius(restir.hole_fill_radius);
  o.set_silhouette_band(restir.silhouette_band);
  o.set_reveal_lookahead(restir.reveal_lookahead);
  o.set_deep_backup(restir.deep_backup);
  o.set_layer_mode(v1::LAYER_MODE_ACTIVE);
  o.set_lod_matching(restir.lod_matching);
  o.set_lod_vertices(v1::LOD_VERTICES_BOTH);
  o.set_splats_per_frame(1);
  o.set_exposure(0.0f);
  o.MergeFrom(requested);  // proto3 optional: only fields that are set overwrite
  normalize(o);
  return o;
}

std::string shift_name(v1::Shift s) { return s == v1::SHIFT_RECONNECTION ? "reconnection" : "hybrid"; }
std::string mis_name(v1::Mis m) { return m == v1::MIS_BALANCE ? "balance" : "pairwise"; }
std::string suffix_name(v1::Suffix s) {
  switch (s) {
    case v1::SUFFIX_REPLAY: return "replay";
    case v1::SUFFIX_CACHED: return "cached";
    case v1::SUFFIX_FAIL: return "fail";
    default: return "auto";
  }
}
std::string layer_mode_name(v1::LayerMode m) {
  switch (m) {
    case v1::LAYER_MODE_UNIFORM: return "uniform";
    case v1::LAYER_MODE_NO_DEPTH_RANGES: return "no-depth-ranges";
    default: return "active";
  }
}
std::string lod_vertices_name(v1::LodVertices v) {
  switch (v) {
    case v1::LOD_VERTICES_PRIMARY: return "primary";
    case v1::LOD_VERTICES_RECONNECTION: return "reconnection";
    default: return "both";
  }
}
std::string lod_mapping_name(v1::LodMapping m) {
  switch (m) {
    case v1::LOD_MAPPING_OFF: return "off";
    case v1::LOD_MAPPING_UV: return "uv";
    default: return "auto";
  }
}

}  // namespace strata::service
