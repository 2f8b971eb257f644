#version 460
// Pass `primary` (stage primary; docs/ARCHITECTURE.md): the visibility buffer. Per pixel one
// camera ray, traced once, with its camera sample (restir/primary_data.h): with PRIMARY_CENTRE the
// ray through the pixel centre and the lens centre at the frame's instant; with PRIMARY_DOMAIN the
// pixel's camera sample of this frame, whose hit is the primary vertex of the pixel's domain (the
// initial pass starts its paths there and every shift into the domain starts there, so no shift
// traces a camera ray). The temporal stages (gather backprojection, splatting's backup and
// confidence), the spatial neighbour filter and the disocclusion mask read its hit instead of
// tracing the same ray again.
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "include/bindings.h"
#include "include/frame_data.h"
#include "include/scene_bridge.glsl"
#include "restir/centre_surface.glsl"
#include "restir/rng_streams.h"

layout(set = 0, binding = BINDING_PRIMARY, std430) writeonly buffer Primary { GpuPrimaryHit b_primary[]; };
#ifdef STRATA_TEXTURES
// With PRIMARY_DOMAIN, each entry's material at its primary footprint (restir/primary_data.h): the
// initial pass and every shift into the domain read it instead of filtering its textures again.
layout(set = 0, binding = BINDING_PRIMARY_MATERIAL, std430) writeonly buffer PrimaryMaterial { GpuPrimaryMaterial b_primary_material[]; };
#endif

#include "sampling/warp.h"
#include "include/camera.glsl"
#include "restir/camera_sample.glsl"

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= u_frame.width || pixel.y >= u_frame.height) return;
  uint index = pixel.y * u_frame.width + pixel.x;
  CameraSample cs;
  cs.jitter = vec2(0.5);
  cs.lens = vec2(0.5);
  cs.time = 1.0;  // the frame's instant: the shutter's close (include/shutter.h)
  GpuCamera camera = u_frame.camera;
  if (u_frame.primary_mode == PRIMARY_DOMAIN) {
    // The key of the initial pass's first candidate path, so that its camera sample is this one.
    cs = camera_sample(rng_key(index, RNG_STREAM_PATH_FIRST, u_frame.frame_index, u_frame.seed));
    camera = camera_at(false, cs.time);
  }
  vec3 origin;
  vec3 dir;
  primary_ray(camera, vec2(pixel), cs.jitter, cs.lens, origin, dir);
  RayHit h;
  GpuPrimaryHit p;
  p.t = 0.0;
  p.instance = 0u;
  p.geometry = 0u;
  p.triangle = 0u;
  p.bary = vec2(0.0);
  p.lod = 0u;
  p.flags = 0u;
  p.jitter = cs.jitter;
  p.lens = packUnorm2x16(cs.lens);
  p.time = cs.time;
  p.position_area = vec4(0.0);
  p.geo_normal_material = vec4(0.0);
  p.shading_normal_kind = vec4(0.0);
  if (trace_closest(origin, dir, RAY_UNBOUNDED, h)) {
    p.t = h.t;
    p.instance = h.instance;
    p.geometry = h.geometry;
    p.triangle = h.triangle;
    p.bary = h.bary;
    p.lod = instance_in(false, h.instance).lod;
    p.flags = PRIMARY_HIT;
    // Its surface in this frame, so that no later stage loads it from the mesh again.
    SurfaceHit s = load_hit(h);
    p.position_area = vec4(s.position, s.area);
    p.geo_normal_material = vec4(s.geo_normal, uintBitsToFloat(s.material));
    float footprint = primary_footprint(camera_spread(false), s.position, dot(s.geo_normal, dir));
#ifdef STRATA_TEXTURES
    MaterialFactors f = material_factors(s, footprint);
    SurfaceMaterial m = material_with(s.material, s.triangle_index, f);
    if (u_frame.primary_mode == PRIMARY_DOMAIN) {
      b_primary_material[index].base_color_metallic = f.base_color_metallic;
      b_primary_material[index].emission_roughness = f.emission_roughness;
    }
#else
    SurfaceMaterial m = material_at(s, footprint);
#endif
    p.shading_normal_kind = vec4(s.shading_normal, uintBitsToFloat(surface_kind(m)));
  }
  b_primary[index] = p;
}
