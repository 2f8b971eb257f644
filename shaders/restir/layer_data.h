// Pixel-layer domains of restir-multilayer (the ML paper; docs/ARCHITECTURE.md, "Pixel layers"):
// what the domain_init stage keeps per domain (pixel, layer) besides its representative hit (the
// visibility buffer's entry of that domain: restir/primary_data.h, indexed by domain_index).
//
// Layers. Layer 0 is the front layer, the first surface along the pixel-centre ray (the image).
// Layer i >= 1 is the i-th front-facing surface behind it: ML Sec. 5 keeps the odd-numbered hits
// (2i-1), which is the same on closed meshes and also right for single-sided planes, whose back
// faces no ray meets. Its representative hit c_{p,i} is that hit of the pixel-centre ray, and its
// depth range D_i = [L_i, R_i] = [(1-e)t, (1+e)t] around the hit's distance t, clamped to the
// midpoint where it overlaps a neighbouring layer's (ML Sec. 5). A deep domain integrates I_i of
// ML Eq. 3 over the paths whose primary vertex lies in its domain A_i of ML Eq. 4.
#ifndef STRATA_LAYER_DATA_H
#define STRATA_LAYER_DATA_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

CONST_DEF uint LAYERS_MAX = 8u;  // the `layers` option's upper bound (restir/restir_limits.h)

// GpuDomainRange::flags
CONST_DEF uint DOMAIN_HIT = 1u;        // the pixel-centre ray has this layer: the representative hit exists
CONST_DEF uint DOMAIN_ACTIVE = 2u;     // takes part in this frame's resampling (front layer: always, with a hit)
CONST_DEF uint DOMAIN_PROPAGATES = 4u; // activated by propagation (or the front layer): its representative hit
                                       // activates next frame's domains (ML 4.3); hole-filled ones do not
CONST_DEF uint DOMAIN_FILLED = 8u;     // active by hole filling only (ML 4.3: sampling only)
CONST_DEF uint DOMAIN_DISOCCLUDED = 16u;  // front layer: its representative hit was hidden from the previous camera
CONST_DEF uint DOMAIN_COVERED = 32u;      // front layer, disoccluded: a splat from a previous deep domain landed, or the deep backup (ML Table 1)
CONST_DEF uint DOMAIN_SILHOUETTE = 64u;   // front layer: a 4-neighbour's centre ray sees another surface (another instance,
                                          // nothing, or a depth more than SILHOUETTE_DEPTH_RATIO apart): an edge that
                                          // can uncover what lies behind the pixels near it
CONST_DEF uint DOMAIN_DORMANT = 128u;     // deep, activated by propagation but not predicted to be uncovered within
                                          // reveal_lookahead frames (without a prediction: farther than silhouette_band from
                                          // every silhouette): its representative hit propagates, it samples nothing (not active)
CONST_DEF uint DOMAIN_HELD = 256u;        // front layer, disoccluded: its representative hit, moved back, lies in the depth
                                          // range of an active previous deep domain (the deep backup's domain)
CONST_DEF uint DOMAIN_PREDICTED = 512u;   // deep, reveal_lookahead > 0: its hit's and the front hit's motion over the last
                                          // frame are known (both moved back into the previous image)
CONST_DEF uint DOMAIN_REVEALING = 1024u;  // deep, predicted: the front layer moves off it within reveal_lookahead frames
                                          // if both keep that motion (domain_build's reveal prediction)
CONST_DEF float SILHOUETTE_DEPTH_RATIO = 0.05f;

CONST_DEF uint OCCLUDER_NONE = 0xFFFFFFFFu;  // a mark no propagated hit set (GpuDomainMark)

// LAYER_MODE_*: how domains are chosen and how a splat finds its layer (ML Table 1, Fig. 5).
CONST_DEF uint LAYER_MODE_ACTIVE = 0u;     // restir-multilayer: active domains, depth ranges
CONST_DEF uint LAYER_MODE_UNIFORM = 1u;    // every layer of every pixel active, layer by stepping rays, no ranges
CONST_DEF uint LAYER_MODE_NO_RANGES = 2u;  // active domains, layer by stepping rays (Table 1 "w/o ranges")

struct GpuDomainRange {
  float range_min;  // L_i: camera distance
  float range_max;  // R_i
  uint flags;       // DOMAIN_*
  uint occluder;    // the instance of the layer in front of the representative hit (OCCLUDER_NONE for layer 0)
};

// The occluders (instance ids) of the representative hits propagated into a domain this frame,
// the least and the greatest (ML Sec. 5's occluder check compares them with the domain's own; two
// different occluders among several marks are kept exactly, more are rare). Both fields start at
// OCCLUDER_NONE (the buffer is filled with ones) and are lowered by atomicMin: the greatest is kept
// as its complement ~occluder. occluder_min = OCCLUDER_NONE: no mark.
struct GpuDomainMark {
  uint occluder_min;
  uint occluder_max;  // ~ the greatest occluder
};

// The compacted list's arguments: a VkDispatchIndirectCommand, then the list's length.
struct GpuDomainArgs {
  uint groups_x;
  uint groups_y;
  uint groups_z;
  uint count;
};

// The arguments buffer holds two: DOMAIN_ARGS_ACTIVE for the list of active deep domains (from the
// list's start), DOMAIN_ARGS_DORMANT for the dormant ones (from the list's end backwards).
CONST_DEF uint DOMAIN_ARGS_ACTIVE = 0u;
CONST_DEF uint DOMAIN_ARGS_DORMANT = 1u;

CONST_DEF uint DOMAIN_LIST_GROUP = 64u;  // threads per workgroup of a list dispatch (local_size_x)

// Where the j-th dormant deep domain of a frame's list lies: the list holds (k - 1) x pixels slots,
// the active domains from the first, the dormant ones from the last backwards.
INLINE uint dormant_list_slot(uint j, uint layers, uint width, uint height) { return (layers - 1u) * width * height - 1u - j; }

STRATA_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(strata::gpu::GpuDomainRange) == 16);
static_assert(sizeof(strata::gpu::GpuDomainArgs) == 16);
#endif
#endif
