// Per-frame constants and counters shared by the host and the passes.
#ifndef STRATA_FRAME_DATA_H
#define STRATA_FRAME_DATA_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

// Camera in render space. right/up are scaled by tan(yfov/2) and aspect. At a frame's instant the
// camera is at the origin; over an open shutter (camera_at in restir/path_vertex.glsl) it moves.
struct GpuCamera {
  vec4 forward;        // xyz unit view direction
  vec4 right;          // xyz = unit right * tan_half * aspect
  vec4 up;             // xyz = unit up * tan_half
  vec4 lens;           // x aperture radius, y focus distance
  vec4 position;       // xyz lens centre (0 at the frame's instant)
};

// The camera's motion over a frame's shutter (scene/shutter.h; RS-supp 3.3.1), relative to the
// frame's camera, where the shutter closes. At shutter time s in [0, 1) (0 = opening) the camera is
// at (1 - s) open_position, turned by (1 - s) angle about `axis`, with the field of view and lens
// interpolated linearly; the frame's camera is the limit s -> 1.
struct GpuShutter {
  vec4 open_position;  // xyz position at the opening (render space); w = 1: the camera moves (motion blur), 0: an instant
  vec4 rotation;       // xyz unit axis, w angle (radians) turning the closing orientation into the opening one
  vec4 open_lens;      // x yfov at the opening, y aperture there, z focus distance there, w yfov at the close
};

struct GpuFrameConstants {
  GpuCamera camera;
  GpuShutter shutter;
  vec4 environment;          // rgb constant environment radiance (without a map), a = 1 if the environment is sampled by NEE
  uint width;
  uint height;
  uint frame_index;
  uint seed;
  uint samples_per_pixel;    // this frame's total; dispatches add GpuDispatchConstants::sample_count each
  uint primary_mode;         // PRIMARY_CENTRE or PRIMARY_DOMAIN: the ray of the visibility buffer (restir/primary_data.h)
  uint max_depth;            // path vertices after the camera
  uint emitter_count;
  float total_emitter_power;
  float env_select_prob;     // probability that NEE picks the environment instead of an emitter
  uint history_flags;        // HISTORY_*: what the previous frame's state (below) may be used for
  uint time_partitions;      // K of multi-splatting over this frame's shutter (RS-main Eq. 19; 1 when it is an instant)
  // The previous frame (docs/ARCHITECTURE.md, State, session state), in the previous frame's render space:
  // its camera, and its light-selection totals so that target functions and MIS weights of
  // reverse shifts are evaluated exactly as that frame's passes evaluated them.
  GpuCamera prev_camera;
  GpuShutter prev_shutter;
  float prev_total_emitter_power;
  float prev_env_select_prob;
  uint prev_width;
  uint prev_height;
  // Punctual lights: entries emitter_count .. emitter_count + light_count - 1 of the light table,
  // their GpuPunctualLight records by device address (a buffer reference, so that a scene without
  // them binds nothing; include/scene_lights.glsl), of this frame and of the previous one (its
  // render space; this frame's own without history). 0 without punctual lights.
  uint light_count;
  uint pad0;
  uvec2 lights;
  uvec2 prev_lights;
  // The environment map's GpuEnvironmentMap record by device address (include/environment_data.h;
  // read only where SPEC_ENV_MAP is on), 0 for the constant environment.
  uvec2 environment_map;
  // The light trees of this frame and the previous one (its render space; this frame's own without
  // history) by device address (include/light_tree_data.h; read only where SPEC_LIGHT_TREE is on).
  uvec2 light_tree;
  uvec2 prev_light_tree;
};

// history_flags bits.
CONST_DEF uint HISTORY_VALID = 1u;         // a previous frame exists (TLAS, instances and camera bound)
CONST_DEF uint HISTORY_SCENE_MOVED = 2u;   // some instance changed since then (INSTANCE_CHANGED_* says which)
CONST_DEF uint HISTORY_LIGHTS_RESELECTED = 4u;  // light selection (emitter table or environment share) differs:
                                                // the same random numbers choose another light in each frame
CONST_DEF uint HISTORY_CAMERA_STILL = 8u;  // the camera (and its shutter) is the previous frame's
CONST_DEF uint HISTORY_LIGHTS_MOVED = 16u; // a punctual light moved or turned (HISTORY_SCENE_MOVED is set with it)
CONST_DEF uint HISTORY_LIGHTS_CHANGED = 32u;  // with the light tree: some light moved, turned, changed power or level,
                                              // so a light's probability at a point may differ between the frames

// primary_mode: which camera ray the primary stage traces per pixel (restir/primary_data.h).
CONST_DEF uint PRIMARY_CENTRE = 0u;  // through the pixel centre and the lens centre, at the frame's instant
CONST_DEF uint PRIMARY_DOMAIN = 1u;  // the pixel's camera sample of the frame: its domain's primary vertex

// Push constants of a dispatch: a frame's samples may be split over several dispatches.
struct GpuDispatchConstants {
  uint sample_base;   // index of the first sample in this dispatch (decorrelates the RNG streams)
  uint sample_count;
};

// Counter slots in the counters buffer (uint each), reduced into the frame statistics.
CONST_DEF uint COUNTER_RAYS_PRIMARY = 0u;
CONST_DEF uint COUNTER_RAYS_BOUNCE = 1u;
CONST_DEF uint COUNTER_RAYS_SHADOW = 2u;
CONST_DEF uint COUNTER_NONFINITE_REJECTED = 3u;
CONST_DEF uint COUNTER_PATHS = 4u;
// ReSTIR passes: rays each pass traced, shifts attempted and failed by reason (restir_data.h).
CONST_DEF uint COUNTER_RAYS_INITIAL = 5u;
CONST_DEF uint COUNTER_RAYS_TEMPORAL = 6u;
CONST_DEF uint COUNTER_RAYS_SPATIAL = 7u;
CONST_DEF uint COUNTER_TEMPORAL_SHIFTS = 8u;        // shifts attempted (each direction counts)
CONST_DEF uint COUNTER_SPATIAL_SHIFTS = 9u;
CONST_DEF uint COUNTER_TEMPORAL_NO_HISTORY = 10u;   // pixels whose backprojection found no history
CONST_DEF uint COUNTER_TEMPORAL_SELECTED = 11u;     // pixels whose output sample came from history
CONST_DEF uint COUNTER_SPATIAL_SELECTED = 12u;      // pixels whose output sample came from a neighbour
CONST_DEF uint COUNTER_TEMPORAL_INVALID = 13u;      // biased temporal: history refused by the heuristic validation
CONST_DEF uint COUNTER_SPLATS_LANDED = 14u;         // restir-splat: previous reservoirs that landed in a pixel
CONST_DEF uint COUNTER_SPLATS_MAX = 15u;            // restir-splat: most splats in one pixel (atomicMax)
CONST_DEF uint COUNTER_TEMPORAL_FAIL = 16u;         // + reason, SHIFT_REASONS slots
CONST_DEF uint COUNTER_SPATIAL_FAIL = 24u;          // + reason
CONST_DEF uint COUNTER_SPLAT_BACKUP_SELECTED = 32u; // restir-splat-backup: pixels whose output is the backup sample
CONST_DEF uint COUNTER_SPLATS_OFFSCREEN = 33u;      // restir-splat: forward splats that projected outside the image
CONST_DEF uint COUNTER_SPLATS_OCCLUDED = 34u;       // restir-splat: forward splats whose primary hit is not visible now
CONST_DEF uint COUNTER_SUFFIX_REPLAYED = 35u;      // temporal shifts that traced their suffix again (restir/suffix_replay.glsl)
CONST_DEF uint COUNTER_SUFFIX_KEPT = 36u;          // temporal shifts that kept the stored suffix (unchanged scene, or `cached`)
CONST_DEF uint COUNTER_RAYS_REPLAY = 37u;          // rays of suffix replays, of the pass temporal / splat_project
CONST_DEF uint COUNTER_SPATIAL_FILTERED = 38u;      // spatial: neighbour candidates refused by the surface filter
CONST_DEF uint COUNTER_RAYS_REPLAY_RESAMPLE = 39u; // rays of suffix replays in splat_resample (reverse splats, backup)
// restir-multilayer (ML Table 1; restir/layer_data.h):
CONST_DEF uint COUNTER_DOMAINS_ACTIVE = 40u;        // + layer (LAYERS_MAX slots): active domains by layer
CONST_DEF uint COUNTER_DOMAINS_PROPAGATED = 48u;    // deep domains activated by a propagated representative hit
CONST_DEF uint COUNTER_DOMAINS_FILLED = 49u;        // deep domains activated by hole filling only
CONST_DEF uint COUNTER_DOMAINS_UNIFORM = 50u;       // deep domains a uniform k-layer scheme keeps (layers the centre ray found)
CONST_DEF uint COUNTER_DOMAINS_OCCLUDER = 51u;      // propagated marks refused by the occluder check (ML Sec. 5)
CONST_DEF uint COUNTER_DISOCCLUDED = 52u;           // front-layer pixels whose centre hit was hidden from the previous camera
CONST_DEF uint COUNTER_DISOCCLUDED_COVERED = 53u;   // of those, pixels that received a sample from a previous deep domain (splat or deep backup)
CONST_DEF uint COUNTER_RAYS_DOMAIN_INIT = 54u;      // rays of the domain_init passes
CONST_DEF uint COUNTER_SPLAT_RANGE_RAYS = 55u;      // closest-hit queries restricted to a depth range (layer assignment)
CONST_DEF uint COUNTER_SPLAT_STEP_RAYS = 56u;       // stepping rays of the layer assignment without depth ranges
CONST_DEF uint COUNTER_SPLATS_DEEP = 57u;           // forward splats that landed in a deep domain
CONST_DEF uint COUNTER_SPLATS_NO_LAYER = 58u;       // forward splats hidden now and in no active domain's depth range
CONST_DEF uint COUNTER_DISOCCLUSION_BOOSTED = 59u;  // front-layer pixels no splat reached that took disocclusion_initial_candidates
// LoD-aware reuse (restir/lod_mapping.h): resolutions of a point across a LoD switch, by outcome.
CONST_DEF uint COUNTER_LOD_MAPPINGS = 60u;          // tau attempted (mapping on for that vertex kind)
CONST_DEF uint COUNTER_LOD_UNIQUE = 61u;            // ... mapped, one point on each side
CONST_DEF uint COUNTER_LOD_MATCHED = 62u;           // ... mapped by Alg. 1 (several points share the UV)
CONST_DEF uint COUNTER_LOD_FAIL_OUTSIDE = 63u;      // ... no point of the target level has the UV
CONST_DEF uint COUNTER_LOD_FAIL_AMBIGUOUS = 64u;    // ... several share it, unmatched (or matching off)
CONST_DEF uint COUNTER_LOD_FAIL_DEGENERATE = 65u;   // ... a degenerate UV triangle
CONST_DEF uint COUNTER_LOD_UV_RAYS = 66u;           // UV-space queries
CONST_DEF uint COUNTER_LOD_REFUSED = 67u;           // points on another level that were not mapped (mapping off)
CONST_DEF uint COUNTER_DISOCCLUDED_HELD = 68u;     // restir-multilayer: disoccluded pixels whose hit an active previous deep domain's depth range held
CONST_DEF uint COUNTER_DOMAINS_DORMANT = 69u;      // restir-multilayer: propagated deep domains far from every silhouette (tracked, not sampled)
CONST_DEF uint COUNTER_DISOCCLUDED_SPLATTED = 70u;  // restir-multilayer: disoccluded pixels a splat from a previous deep domain reached
CONST_DEF uint COUNTER_DISOCCLUDED_BACKUP = 71u;    // restir-multilayer: disoccluded pixels the deep backup's sample shifted into
CONST_DEF uint COUNTER_COUNT = 72u;

STRATA_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(strata::gpu::GpuFrameConstants) == 384);
#endif
#endif
