#version 460
// Pass `shade` (stage shade): each pixel's estimate from the last pass that resampled it, the
// conditional expectation of f(Y) W_Y (GRIS, RS-main Eq. 5) over that pass's candidates
// (restir/gris.h, gris_stream_path), plus the initial pass's estimate of what the camera rays see directly
// (paths of one segment, which are not resampled: restir_initial.comp), added to the accumulation
// buffer as one sample.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "include/bindings.h"
#include "include/frame_data.h"
#include "restir/domain.h"

layout(set = 0, binding = BINDING_FRAME, std140) uniform Frame { GpuFrameConstants u_frame; };
layout(set = 0, binding = BINDING_COUNTERS, std430) buffer Counters { uint b_counters[]; };
layout(set = 0, binding = BINDING_CONTRIBUTION, std430) readonly buffer Contribution { vec4 b_contribution[]; };
layout(set = 0, binding = BINDING_ACCUM, std430) buffer Accum { vec4 b_accum[]; };

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= u_frame.width || pixel.y >= u_frame.height) return;
  uint index = pixel.y * u_frame.width + pixel.x;
  uint domain = domain_index(pixel, 0u, u_frame.width, u_frame.height);  // the front layer is the image
  uint pixels = u_frame.width * u_frame.height;
  uint domains = pixels;  // one layer
  vec3 l = b_contribution[contribution_estimate_index(domain, domains, pixels)].rgb;
  l += b_contribution[contribution_emission_index(index, domains)].rgb;
  // A non-finite or negative estimate never reaches a pixel; it is counted.
  if (any(isnan(l)) || any(isinf(l)) || any(lessThan(l, vec3(0.0)))) {
    atomicAdd(b_counters[COUNTER_NONFINITE_REJECTED], 1u);
    l = vec3(0.0);
  }
  b_accum[index] += vec4(l, 1.0);
}
