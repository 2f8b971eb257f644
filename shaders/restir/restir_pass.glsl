// Declarations every ReSTIR pass shares: method constants, counters, the reservoir buffers, and
// packing helpers; and the ReSTIR library's context (restir/context.glsl) implemented on them and
// on the frame's constants (declared by the scene bridge). A pass includes it after the scene bridge.
#ifndef STRATA_RESTIR_PASS_GLSL
#define STRATA_RESTIR_PASS_GLSL

#include "include/bindings.h"
#include "include/frame_data.h"
#include "restir/domain.h"
#include "restir/gris.h"
#include "restir/reservoir.h"
#include "restir/restir_data.h"
#include "restir/rng_streams.h"
#include "restir/context.glsl"

layout(set = 0, binding = BINDING_RESTIR, std140) uniform Restir { GpuRestirConstants u_restir; };
layout(set = 0, binding = BINDING_COUNTERS, std430) buffer Counters { uint b_counters[]; };
layout(set = 0, binding = BINDING_RESERVOIRS_OUT, std430) buffer ReservoirsOut { PackedReservoir b_out[]; };
layout(set = 0, binding = BINDING_CONTRIBUTION, std430) buffer Contribution { vec4 b_contribution[]; };
#ifdef STRATA_TEXTURES
// Fixed primary vertices' materials (restir/primary_data.h, GpuPrimaryMaterial), both frames.
layout(set = 0, binding = BINDING_PRIMARY_MATERIAL, std430) readonly buffer PrimaryMaterial { GpuPrimaryMaterial b_primary_material[]; };
layout(set = 0, binding = BINDING_PRIMARY_MATERIAL_PREV, std430) readonly buffer PrimaryMaterialPrev { GpuPrimaryMaterial b_primary_material_prev[]; };
#endif

// The library's context (restir/context.glsl).
uvec2 image_size(bool prev) { return prev ? uvec2(u_frame.prev_width, u_frame.prev_height) : uvec2(u_frame.width, u_frame.height); }
Rng frame_rng(uint key, uint salt) { return rng_init(key, salt, u_frame.frame_index, u_frame.seed); }
uint frame_key(uint key, uint stream) { return rng_key(key, stream, u_frame.frame_index, u_frame.seed); }
uint history_flags() { return u_frame.history_flags; }
uint primary_mode() { return u_frame.primary_mode; }
uint time_partitions() { return u_frame.time_partitions; }
uint restir_layers() { return u_restir.layers; }
uint restir_max_segments() { return u_restir.max_segments; }
uint restir_light_candidates() { return u_restir.light_candidates; }
uint restir_shift_mode() { return u_restir.shift_mode; }
uint restir_suffix_mode() { return u_restir.suffix_mode; }
float restir_spatial_radius() { return u_restir.spatial_radius; }
void counter_add(uint counter, uint n) { atomicAdd(b_counters[counter], n); }
void counter_max(uint counter, uint n) { atomicMax(b_counters[counter], n); }

// In textured variants the primary stage's record of the entry's material: its textures are
// filtered once per pixel and frame, and the initial pass and every shift into the domain see the
// same material. Elsewhere the material record itself.
SurfaceMaterial fixed_primary_material(bool prev, uint entry, SurfaceHit s) {
#ifdef STRATA_TEXTURES
  // Member by member: glslang stores a whole buffer struct with the wrong type.
  MaterialFactors f;
  if (prev) {
    f.base_color_metallic = b_primary_material_prev[entry].base_color_metallic;
    f.emission_roughness = b_primary_material_prev[entry].emission_roughness;
  } else {
    f.base_color_metallic = b_primary_material[entry].base_color_metallic;
    f.emission_roughness = b_primary_material[entry].emission_roughness;
  }
  return material_with(s.material, s.triangle_index, f);
#else
  return material_of(s.material);
#endif
}

#ifdef STRATA_HISTORY
// Counts a surface resolution across a LoD switch (COUNTER_LOD_*).
void count_lod_mapping(ResolvedSurface r) {
  if (r.lod_mapping == LOD_MAPPING_NONE) return;
  if (r.lod_mapping == LOD_FAIL_OFF) {
    counter_add(COUNTER_LOD_REFUSED, 1u);
    return;
  }
  counter_add(COUNTER_LOD_MAPPINGS, 1u);
  counter_add(COUNTER_LOD_UV_RAYS, r.uv_rays);
  uint c = r.lod_mapping == LOD_MAPPED_UNIQUE    ? COUNTER_LOD_UNIQUE
           : r.lod_mapping == LOD_MAPPED_MATCHED ? COUNTER_LOD_MATCHED
           : r.lod_mapping == LOD_FAIL_OUTSIDE   ? COUNTER_LOD_FAIL_OUTSIDE
           : r.lod_mapping == LOD_FAIL_AMBIGUOUS ? COUNTER_LOD_FAIL_AMBIGUOUS
                                                 : COUNTER_LOD_FAIL_DEGENERATE;
  counter_add(c, 1u);
}
#endif

// Per-pixel data (random streams, the visibility buffer): row-major pixel index.
uint pixel_index(uvec2 p) { return p.y * u_frame.width + p.x; }
bool in_image(ivec2 p) { return p.x >= 0 && p.y >= 0 && p.x < int(u_frame.width) && p.y < int(u_frame.height); }

// Per-domain data (reservoirs, contributions, splat keys) is indexed by domain_index only
// (restir/domain.h): the domain of layer `layer` at a pixel of the current or the previous frame.
uint domain_of(uvec2 pixel, uint layer) { return domain_index(pixel, layer, u_frame.width, u_frame.height); }
uint prev_domain_of(uvec2 pixel, uint layer) { return domain_index(pixel, layer, u_frame.prev_width, u_frame.prev_height); }
uint domain_count() { return u_frame.width * u_frame.height * u_restir.layers; }  // k layers (1 but for restir-multilayer)
uint prev_domain_count() { return u_frame.prev_width * u_frame.prev_height * u_restir.layers; }
// The pixel and layer of domain index d (the inverse of domain_index) in the current or previous frame.
uvec2 domain_pixel_of(uint d) { return domain_pixel(d % (u_frame.width * u_frame.height), u_frame.width); }
uint domain_layer_of(uint d) { return d / (u_frame.width * u_frame.height); }
uvec2 prev_domain_pixel_of(uint d) { return domain_pixel(d % (u_frame.prev_width * u_frame.prev_height), u_frame.prev_width); }
uint prev_domain_layer_of(uint d) { return d / (u_frame.prev_width * u_frame.prev_height); }

// The contribution buffer (restir/domain.h) holds f(Y) of the reservoir of every domain, then per
// pixel its estimate of what its camera rays see directly, x_1's emission or the environment
// (written by the initial pass, added by the shade pass; paths of one segment are never resampled:
// restir_initial.comp), then every domain's estimate from its last resampling (store_output).
uint primary_emission_index(uvec2 pixel) { return contribution_emission_index(pixel_index(pixel), domain_count()); }
uint estimate_index(uint domain) { return contribution_estimate_index(domain, domain_count(), u_frame.width * u_frame.height); }

Reservoir reservoir_empty() {
  Reservoir r;
  r.y.x1 = surface_none();
  r.y.xk = surface_none();
  r.y.xk_direction = vec3(0.0, 0.0, 1.0);
  r.y.xk_radiance = vec3(0.0);
  r.y.k = 0u;
  r.y.segments = 0u;
  r.y.flags = 0u;
  r.y.seed = 0u;
  r.y.lens = vec2(0.5);
  r.y.time = 0.0;
  r.y.jitter = vec2(0.5);
  r.y.density = 0.0;
  r.y.light_pdf_end = 0.0;
  r.y.suffix_density = 1.0;
  r.y.light_index = 0u;
  r.ucw = 0.0;
  r.confidence = 0.0;
  r.p_hat = 0.0;
  return r;
}

// The confidence cap of the domain whose primary vertex is visibility-buffer entry `e` of this frame
// (RS-main 3.4; docs/ARCHITECTURE.md, "Confidence cap"): still_confidence_cap where nothing moved
// since the previous frame (the camera, and no instance anywhere: an object that moves changes the
// light arriving at still surfaces too, through its shadows and reflections), else confidence_cap.
// It reads the frame's flags and geometry only, so like any confidence weights it leaves the MIS
// weights unbiased. For the splat methods `e` is the pixel-centre hit.
float confidence_cap_of(GpuPrimaryHit e) {
  bool still = (u_frame.history_flags & HISTORY_CAMERA_STILL) != 0u && (u_frame.history_flags & HISTORY_SCENE_MOVED) == 0u &&
               (e.flags & PRIMARY_HIT) != 0u;
  return still ? u_restir.still_confidence_cap : u_restir.confidence_cap;
}

bool reservoir_valid(Reservoir r) { return (r.y.flags & SAMPLE_VALID) != 0u && r.ucw > 0.0 && r.p_hat > 0.0; }

// Writes the pass's output reservoir, f(Y) and the domain's estimate over the pass's candidates
// (GrisState.estimate) of domain `index`; a non-finite weight or estimate empties it
// (docs/ARCHITECTURE.md, "Robustness") and is counted.
void store_output(uint index, Reservoir r, vec3 f, vec3 estimate) {
  bool finite = !(isnan(r.ucw) || isinf(r.ucw) || isnan(r.p_hat) || isinf(r.p_hat) || any(isnan(f)) || any(isinf(f)) ||
                  any(isnan(estimate)) || any(isinf(estimate)));
  if (!finite) {
    counter_add(COUNTER_NONFINITE_REJECTED, 1u);
    float c = r.confidence;
    r = reservoir_empty();
    r.confidence = isnan(c) || isinf(c) ? 0.0 : c;
    f = vec3(0.0);
    estimate = vec3(0.0);
  }
  b_out[index] = pack_reservoir(r);
  b_contribution[index] = vec4(f, 0.0);
  b_contribution[estimate_index(index)] = vec4(estimate, 0.0);
}

// The last step of every resampling pass (temporal, spatial, splat_resample): the output reservoir
// of domain `index` is the selected candidate `selected` (its f(Y) `f`) with the stream's p-hat of
// it and its unbiased contribution weight W = (1 / p-hat(Y)) sum_i w_i (RS-main Eq. 5), and
// `confidence`; empty, keeping the confidence, when the stream selected nothing. It is written
// with the domain's estimate over the stream's candidates (store_output).
void finalise_reservoir(uint index, GrisState st, Reservoir selected, vec3 f, float confidence) {
  Reservoir r = selected;
  r.p_hat = st.selected_p_hat;
  r.ucw = gris_ucw(st);  // RS-main Eq. 5
  r.confidence = confidence;
  if (st.selected == GRIS_NONE) {
    r = reservoir_empty();
    r.confidence = confidence;
    f = vec3(0.0);
  }
  if (st.rejected > 0u) counter_add(COUNTER_NONFINITE_REJECTED, st.rejected);
  store_output(index, r, f, st.estimate);
}

#endif
