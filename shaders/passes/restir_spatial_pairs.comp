#version 460
// Pass `spatial pairs` (stage spatial, before restir_spatial.comp; restir/spatial_pairs.glsl): the
// samples of this pixel's paired neighbours, at +o_m and -o_m, shifted into its domain once. Its
// own resampling reads them as the neighbours' forward shifts; each neighbour reads the one of
// this pixel's sample in its record as its reverse shift (RS-main Eq. 7's p-hat from the neighbour's
// domain, for the canonical sample's pairwise MIS weight).
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "include/scene_bridge.glsl"
#include "restir/restir_pass.glsl"
#include "restir/path_space.glsl"
#include "restir/centre_surface.glsl"

layout(set = 0, binding = BINDING_RESERVOIRS_IN, std430) readonly buffer ReservoirsIn { PackedReservoir b_in[]; };
layout(set = 0, binding = BINDING_PRIMARY, std430) readonly buffer Primary { GpuPrimaryHit b_primary[]; };

#include "restir/spatial_pairs.glsl"

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= u_frame.width || pixel.y >= u_frame.height) return;
  GpuPrimaryHit entry = b_primary[pixel_index(pixel)];
  CentreSurface here = centre_surface(entry);
  DomainPrimary dp = domain_primary(entry, pixel_index(pixel));
  ivec2 o[SPATIAL_MAX_PAIR_OFFSETS];
  spatial_pair_offsets(o);
  uint rays = 0u;
  // One shift_path call site for every slot (lavapipe compiles every inlined call separately).
  for (uint slot = 0u; slot < pair_slots(); ++slot) {
    ShiftResult s = shift_none(SHIFT_FAIL_ZERO);
    ivec2 q = ivec2(pixel) + pair_direction(o, slot);
    if (here.valid && in_image(q) && similar_pair(here, centre_surface(b_primary[pixel_index(uvec2(q))]))) {
      Reservoir r = unpack_reservoir(b_in[domain_of(uvec2(q), 0u)]);
      if (reservoir_valid(r)) {
        s = shift_path(false, vec2(pixel), dp, r.y, false);
        rays += s.rays;
        counter_add(COUNTER_SPATIAL_SHIFTS, 1u);
        if (s.reason != SHIFT_OK) counter_add(COUNTER_SPATIAL_FAIL + s.reason, 1u);
      }
    }
    store_pair(pixel, slot, s);
  }
  if (rays > 0u) counter_add(COUNTER_RAYS_SPATIAL, rays);
}
