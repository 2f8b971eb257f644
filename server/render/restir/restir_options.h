#pragma once
// Options of the ReSTIR methods (docs/ARCHITECTURE.md, Methods; docs/OPTIONS.md): what the renderer
// is created with. Each member is described once in the option table (server/options/option_table.h):
// its name, range, help and what a change does; its default is the initializer here. The choices are
// enums whose values are the passes' constants, so that a choice reaches the device unconverted.
// `pt` ignores them.
#include <algorithm>
#include <cstdint>

#include "render/method_table.h"
#include "restir/layer_data.h"
#include "restir/lod_mapping.h"
#include "restir/restir_data.h"
#include "restir/restir_limits.h"

namespace strata::render {

// Shift mappings (RS-main 3): reconnection at x_2 only, or random replay until a reconnectable vertex.
enum class Shift : uint32_t { reconnection = gpu::SHIFT_RECONNECTION, hybrid = gpu::SHIFT_HYBRID };
// MIS weights of spatial resampling (the temporal pair is the same for both).
enum class Mis : uint32_t { balance = gpu::MIS_BALANCE, pairwise = gpu::MIS_PAIRWISE };
// The suffix after x_k when the scene changed between frames (restir/suffix_replay.glsl).
enum class Suffix : uint32_t {
  automatic = gpu::SUFFIX_AUTO,
  replay = gpu::SUFFIX_REPLAY,  // traced again: unbiased
  cached = gpu::SUFFIX_CACHED,  // the stored radiance: biased
  fail = gpu::SUFFIX_FAIL,      // the shift is refused
};
// restir-multilayer: the ML paper's method (active) and its validation variants (Fig. 5, Table 1).
enum class LayerMode : uint32_t {
  active = gpu::LAYER_MODE_ACTIVE,
  uniform = gpu::LAYER_MODE_UNIFORM,
  no_depth_ranges = gpu::LAYER_MODE_NO_RANGES,
};
// How next-event estimation chooses a light: by power (the alias table), by the light tree
// (render/light_tree.h; the device's SPEC_LIGHT_TREE), or automatic: the tree where the scene has
// many bounded lights (render/light_sampler_choice.h).
enum class LightSampler : uint32_t { power = 0, tree = 1, automatic = 2 };
// LoD-aware reuse (the LOD paper; docs/ARCHITECTURE.md, "Surface resolver"): uv where the scene has
// LoD groups (automatic), off (a LoD switch refuses the shifts of its points), or uv (the vertex mapping tau).
enum class LodMapping : uint32_t { automatic = 0, off = 1, uv = 2 };
// The path vertices tau maps (LOD Fig. 5 ablation): a mask of the passes' LOD_VERTEX_* bits.
enum class LodVertices : uint32_t {
  both = gpu::LOD_VERTEX_PRIMARY | gpu::LOD_VERTEX_RECONNECTION,
  primary = gpu::LOD_VERTEX_PRIMARY,
  reconnection = gpu::LOD_VERTEX_RECONNECTION,
};

struct RestirOptions {
  Shift shift = Shift::hybrid;
  Mis mis = Mis::pairwise;
  bool unbiased = true;              // false: the DI tutorial's confidence-only temporal weights (biased)
  Suffix suffix = Suffix::automatic;
  bool temporal = true;              // temporal reuse (gather: backprojection)
  bool spatial = true;               // spatial reuse
  // c_cap of the temporal history where something moved; 0: the method's (MethodSpec::confidence_cap,
  // chosen by measurement: docs/BENCHMARKS.md).
  float confidence_cap = 0.0f;
  uint32_t spatial_neighbors = 2;    // N (chosen by measurement: docs/BENCHMARKS.md, "Spatial reuse: filter and radius")
  float spatial_radius = 0.0f;       // pixels; 0: automatic, default_spatial_radius(height)
  uint32_t initial_candidates = 1;   // N_init paths per pixel for the canonical sample
  uint32_t light_candidates = 1;     // NEE samples per path vertex (the DI tutorial uses 32 at x1)
  bool direct_lighting = false;      // ReSTIR DI: paths of one bounce (camera, x1, light); set by benchmarks, not an option
  uint32_t splats_per_frame = 1;     // restir-splat*: K time partitions over an open shutter (RS-main Eq. 19)
  // Neighbours for pixels whose reservoir holds no history (disoccluded, or the first frame); 0: spatial_neighbors.
  // Chosen by measurement: docs/BENCHMARKS.md, "Warm-up, disocclusions and what the camera sees directly".
  uint32_t disocclusion_spatial_neighbors = 6;
  // G: a pixel at the edge of something the camera sees emitting estimates what it sees directly
  // with G x G stratified camera samples (restir_initial.comp); 1: the domain's camera sample only.
  uint32_t direct_strata = 3;
  // G: gather methods add the albedo control variate to the reflected light of pixels at albedo edges,
  // with G x G stratified camera samples of the albedo (restir_initial.comp, restir_shade.comp;
  // docs/ARCHITECTURE.md, "The albedo control variate"); 1: off.
  uint32_t albedo_strata = 2;
  // The largest b of the colour control variate of the gather and splat methods (restir_shade.comp;
  // docs/ARCHITECTURE.md, "The colour control variate"): the pixel keeps its luminance and takes b of
  // the way towards the colour of its initial paths, b shrinking below this where the window's
  // initial colours spread; 0: off.
  float colour_cv = 0.6f;
  // k of b's shrinkage, colour_cv k / (k + S) (restir/colour_cv.h); 0: b = colour_cv everywhere (the
  // unbiasedness tests use it to give the variate its full weight; an ablation).
  float colour_cv_spread = 0.3f;
  bool temporal_filter = true;       // gather: the history pixel's centre surface must be like this pixel's
  // The confidence cap of a pixel where nothing moved since the previous frame (the camera, and the
  // instance its primary vertex or pixel centre lies on); 0: the moving cap. Chosen by measurement:
  // docs/BENCHMARKS.md, "What the reuse passes spend besides rays".
  float still_confidence_cap = 8.0f;
  // restir-multilayer (the ML paper; docs/ARCHITECTURE.md, "Pixel layers"): k pixel layers per pixel
  // (0: auto, measured from the scene's visible depth complexity on the first frame) and the hole
  // filling radius in pixels (ML 4.3; 0: off).
  uint32_t layers = 0;
  uint32_t hole_fill_radius = 3;
  // restir-multilayer: deep domains farther than this many pixels from every silhouette of the front
  // layer are dormant (tracked, not sampled: docs/ARCHITECTURE.md, "Pixel layers"); 0: off, every
  // activated domain samples (ML 4.3). 1 by measurement on carousel (docs/BENCHMARKS.md): 39-44% of
  // the deep domains, 97% of the coverage, the same disoccluded error.
  uint32_t silhouette_band = 1;
  // restir-multilayer: a deep domain whose hit and front hit both moved back into the previous image
  // samples only when, keeping that motion, the front layer moves off it within this many frames;
  // otherwise it is dormant (docs/ARCHITECTURE.md, "Pixel layers": the reveal prediction; the
  // silhouette band decides for the others). 0: off. 4 by measurement on carousel (docs/BENCHMARKS.md).
  uint32_t reveal_lookahead = 4;
  // restir-multilayer, layer_mode active: the deep backup (docs/ARCHITECTURE.md, "Pixel layers": the deep backup):
  // a disoccluded pixel whose hit an active previous deep domain held takes that domain's reservoir
  // as its backup sample (RS-main 4.2 across layers), so that a splat that missed it is not lost.
  bool deep_backup = true;
  LayerMode layer_mode = LayerMode::active;
  // restir-multilayer: 0 shades the image; i >= 1 writes instead each pixel's layer-i domain
  // estimate (ML Eq. 3: the radiance its deep surface sends to the camera as if nothing hid it;
  // 0 where that domain is inactive). For tests and for looking at a layer.
  uint32_t view_layer = 0;
  // Splat methods: initial candidates of the pixels no temporal splat reached, the ML paper's "more
  // initial spp" disocclusion baseline (Fig. 9); restir-multilayer: of those its domain_build found
  // disoccluded (the landing holes of surfaces that were in view take initial_candidates). 0: the
  // method's (MethodSpec::disocclusion_initial_candidates: restir-multilayer 8, the others
  // initial_candidates); a value equal to initial_candidates turns the boost off.
  uint32_t disocclusion_initial_candidates = 0;
  LodMapping lod_mapping = LodMapping::automatic;
  LightSampler light_sampler = LightSampler::automatic;
  bool lod_matching = true;          // Alg. 1 settles UVs that several points share (else they refuse)
  LodVertices lod_vertices = LodVertices::both;

  // The boost's candidate count in effect for `method` with k pixel layers; 0 where there is none
  // (the method's default needs a deep layer: with one, restir-multilayer is restir-splat's pipeline).
  uint32_t disocclusion_candidates(const MethodSpec& method, uint32_t k) const {
    const uint32_t n = disocclusion_initial_candidates > 0 ? disocclusion_initial_candidates
                       : k > 1                             ? method.disocclusion_initial_candidates
                                                           : 0u;
    return n == initial_candidates ? 0u : n;
  }
  float moving_cap(const MethodSpec& method) const { return confidence_cap > 0.0f ? confidence_cap : method.confidence_cap; }
  float still_cap(const MethodSpec& method) const {
    return still_confidence_cap > 0.0f ? still_confidence_cap : moving_cap(method);
  }
  // Every member within the range of its option-table row; std::invalid_argument naming the first
  // that is not ("restir.<option> = v is outside [lo, hi]"). Defined with the table.
  void validate() const;
  // Whether the primary stage runs and fills the visibility buffer: the method's domains start at
  // its hits (MethodSpec::fixed_primary), or a temporal or spatial stage reads it.
  bool visibility_buffer(bool fixed_primary) const { return fixed_primary || temporal || spatial; }
  // The strata the method's passes use (GpuRestirConstants; the session's decisions say the same):
  // both edge tests read the neighbours' visibility-buffer entries, and the albedo control variate
  // needs the domain's primary vertex as well (gather). direct_strata 1 and albedo_strata 0: off.
  uint32_t direct_strata_used(const MethodSpec& method) const {
    return visibility_buffer(method.fixed_primary) ? direct_strata : 1u;
  }
  uint32_t albedo_strata_used(const MethodSpec& method) const {
    return method.fixed_primary && albedo_strata > 1 ? albedo_strata : 0u;
  }
  // The colour control variate: gather and single-layer splat methods (restir-multilayer's deep
  // domains would write over its per-pixel B and window marks). Without reuse the pixel's estimate
  // is its initial paths' (A = B): nothing to correct, no pass or memory.
  float colour_cv_used(const MethodSpec& method) const {
    return (method.fixed_primary || (method.splatting && !method.layers)) && (temporal || spatial) ? colour_cv : 0.0f;
  }
  // The radius the spatial pass uses for an image `height` pixels high.
  float spatial_radius_pixels(uint32_t height) const { return spatial_radius > 0.0f ? spatial_radius : default_spatial_radius(height); }

  // The automatic radius: a fraction of the image height with a floor in pixels (the references
  // use 20-32 px at 1080p, 2-3% of the height; a floor keeps a few candidate pixels in small
  // images). Chosen by measurement: docs/BENCHMARKS.md, "Spatial reuse: filter and radius".
  static constexpr float spatial_radius_fraction = 0.025f;
  static constexpr float spatial_radius_floor = 4.0f;  // pixels
  // Inline: the service's option defaults use it without the renderer (the fuzz tree links no Vulkan).
  static float default_spatial_radius(uint32_t height) {
    return std::min(std::max(spatial_radius_floor, spatial_radius_fraction * float(height)), gpu::RESTIR_MAX_SPATIAL_RADIUS);
  }
};

}  // namespace strata::render
