// Constants of the ReSTIR passes (one uniform per method instance), shared by host and device.
#ifndef STRATA_RESTIR_DATA_H
#define STRATA_RESTIR_DATA_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

CONST_DEF uint SHIFT_RECONNECTION = 0u;  // reconnect at x_2 only (the base path must allow it)
CONST_DEF uint SHIFT_HYBRID = 1u;        // random replay until the first reconnectable vertex

// What a temporal shift does with the part of a path after its reconnection vertex x_k when the
// scene changed between the two frames (restir/suffix_replay.glsl). `auto` is decided on the host.
CONST_DEF uint SUFFIX_FAIL = 0u;    // the shift fails (SHIFT_FAIL_STALE)
CONST_DEF uint SUFFIX_CACHED = 1u;  // the stored radiance is kept (the references' behaviour; biased)
CONST_DEF uint SUFFIX_REPLAY = 2u;  // the suffix is traced again in the target frame (unbiased)
CONST_DEF uint SUFFIX_AUTO = 3u;    // replay, except a one-segment suffix that no change can reach (kept: exact)

CONST_DEF uint MIS_BALANCE = 0u;   // generalized balance heuristic (RS-main Eq. 6), O(N^2) shifts
CONST_DEF uint MIS_PAIRWISE = 1u;  // confidence-weighted pairwise MIS, O(N) shifts

// flags
CONST_DEF uint RESTIR_UNBIASED = 1u;  // temporal MIS with the reverse shift (Lin 2022); else the DI
                                      // tutorial's confidence weights with heuristic validation
CONST_DEF uint RESTIR_SPLAT_BACKUP = 2u;  // restir-splat-backup: also the backprojected backup sample (RS-main 4.2)
CONST_DEF uint RESTIR_TEMPORAL_FILTER = 4u;  // gather temporal: q's previous centre surface must be like this pixel's
CONST_DEF uint RESTIR_DEEP_BACKUP = 8u;  // restir-multilayer: a disoccluded pixel's backup is the previous deep domain that held it

struct GpuRestirConstants {
  uint initial_candidates;  // N_init paths per pixel
  uint light_candidates;    // NEE samples per vertex
  uint shift_mode;          // SHIFT_*
  uint mis_mode;            // MIS_*
  float confidence_cap;
  float spatial_radius;     // pixels
  uint spatial_neighbors;
  uint flags;               // RESTIR_*
  uint max_segments;        // path length limit (1 bounce for ReSTIR DI: 2 segments)
  uint splats_per_frame;    // K of multi-splatting over an open shutter (RS-main Eq. 19)
  uint suffix_mode;         // SUFFIX_*
  uint disocclusion_spatial_neighbors;  // N for pixels whose reservoir holds no history (0: spatial_neighbors)
  uint direct_strata;       // G: what the camera sees directly is estimated with G x G stratified camera samples (0: the N_init candidates' camera rays)
  float still_confidence_cap;  // the cap of a domain where nothing moved (confidence_cap_of, restir_pass.glsl)
  uint albedo_strata;        // G: the reflected light's albedo control variate takes G x G camera samples at albedo edges (0: off)
  uint layers;               // pixel layers per pixel (restir/layer_data.h; 1 for every single-layer method)
  uint hole_fill_radius;     // restir-multilayer: deep domains within this many pixels of a propagated one are active too (ML 4.3)
  uint layer_mode;           // restir-multilayer: LAYER_MODE_* (the method and its ML validation variants)
  float depth_range_epsilon; // restir-multilayer: a representative hit at t has the depth range [(1-e)t, (1+e)t] (ML Sec. 5)
  uint view_layer;          // restir-multilayer: 0 shades the image; i >= 1 the estimates of layer i's active domains (tests, debugging)
  uint disocclusion_initial_candidates;  // splat methods: candidates of front-layer pixels no splat reached (restir-multilayer: disoccluded ones); 0: none (RestirOptions::disocclusion_candidates)
  uint silhouette_band;     // restir-multilayer: deep domains farther than this many pixels from a front-layer silhouette are dormant (0: off)
  uint reveal_lookahead;    // restir-multilayer: a deep domain whose motion is known samples when predicted to be uncovered within this many frames, else dormant (0: off)
  float colour_cv;          // gather and splat methods: the colour control variate's largest b (restir_shade.comp; 0: off)
  float colour_cv_spread;   // its k (restir/colour_cv.h; 0: b = colour_cv everywhere)
  uint pad0;
  uint pad1;
  uint pad2;
};

// Why a shift failed; counted per pass (COUNTER_SHIFT_* + reason).
CONST_DEF uint SHIFT_OK = 0u;
CONST_DEF uint SHIFT_FAIL_PRIMARY = 1u;    // the replayed primary ray missed, or hit something else
CONST_DEF uint SHIFT_FAIL_REPLAY = 2u;     // a replayed direction was unusable or its ray missed
CONST_DEF uint SHIFT_FAIL_STRUCTURE = 3u;  // the offset path's first reconnectable vertex is not k
CONST_DEF uint SHIFT_FAIL_OCCLUDED = 4u;   // the reconnection segment is blocked
CONST_DEF uint SHIFT_FAIL_JACOBIAN = 5u;   // grazing reconnection or Jacobian out of range
CONST_DEF uint SHIFT_FAIL_STALE = 6u;      // the kept suffix changed with the scene (or LoD switched)
CONST_DEF uint SHIFT_FAIL_ZERO = 7u;       // the offset path carries no light (BSDF or facing)
CONST_DEF uint SHIFT_REASONS = 8u;

STRATA_NAMESPACE_END

#ifdef __cplusplus
#include "include/frame_data.h"
#include "restir/layer_data.h"
static_assert(sizeof(strata::gpu::GpuRestirConstants) == 112);
// The multi-layer counters: one slot per layer.
static_assert(strata::gpu::COUNTER_DOMAINS_ACTIVE + strata::gpu::LAYERS_MAX <= strata::gpu::COUNTER_DOMAINS_PROPAGATED);
// The counter slots of shift failures hold one slot per reason: a new reason must not run into the
// next block of counters (frame_data.h).
static_assert(strata::gpu::COUNTER_TEMPORAL_FAIL + strata::gpu::SHIFT_REASONS <= strata::gpu::COUNTER_SPATIAL_FAIL);
static_assert(strata::gpu::COUNTER_SPATIAL_FAIL + strata::gpu::SHIFT_REASONS <= strata::gpu::COUNTER_SPLAT_BACKUP_SELECTED);
static_assert(strata::gpu::COUNTER_SPLAT_BACKUP_SELECTED < strata::gpu::COUNTER_COUNT);
#endif
#endif
