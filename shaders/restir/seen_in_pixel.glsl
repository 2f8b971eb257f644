// Whether a point is what the camera sees in a pixel, without a ray (domain_propagate: this frame's
// image; domain_build's disocclusion test: the previous frame's). Include after declaring the
// visibility buffers of both frames as b_primary and b_primary_prev, and restir/restir_pass.glsl.
#ifndef STRATA_SEEN_IN_PIXEL_GLSL
#define STRATA_SEEN_IN_PIXEL_GLSL

// A pixel-centre hit within this relative distance of d, on the point's instance, is its surface.
const float SEEN_DEPTH_MARGIN = 0.02;

bool centre_hit_on(GpuPrimaryHit h, uint instance, float d) {
  return (h.flags & PRIMARY_HIT) != 0u && h.instance == instance && abs(h.t - d) <= SEEN_DEPTH_MARGIN * d;
}

// True when the centre hits of `pixel` and of its four neighbours (in the current or previous frame)
// all lie on `instance` at nearly distance d: no silhouette crosses the pixel, so a point of that
// instance at d inside it is seen. False means "trace to know".
bool seen_in_pixel(bool prev, uvec2 pixel, uint instance, float d) {
  const ivec2 offsets[5] = ivec2[5](ivec2(0, 0), ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));
  ivec2 last = ivec2(image_size(prev)) - 1;
  for (uint n = 0u; n < 5u; ++n) {
    uvec2 q = uvec2(clamp(ivec2(pixel) + offsets[n], ivec2(0), last));
    // (if/else, not ?:, so that glslang copies each block's struct member by member)
    GpuPrimaryHit h;
    if (prev) h = b_primary_prev[prev_domain_of(q, 0u)];
    else h = b_primary[domain_of(q, 0u)];
    if (!centre_hit_on(h, instance, d)) return false;
  }
  return true;
}

#endif
