#version 460
// Pass `splat_scan` (restir-splat; RS-supp 3.1 step 2): the exclusive prefix sum of the per-domain
// splat counts, offsets[j] = sum_{l<j} count[l], offsets[N] = the number of splats. One workgroup
// walks the image in chunks of 256 counts (a Hillis-Steele scan in shared memory per chunk).
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 256, local_size_y = 1, local_size_z = 1) in;

#include "include/bindings.h"
#include "include/frame_data.h"
#include "restir/restir_data.h"

layout(set = 0, binding = BINDING_FRAME, std140) uniform Frame { GpuFrameConstants u_frame; };
layout(set = 0, binding = BINDING_RESTIR, std140) uniform Restir { GpuRestirConstants u_restir; };
layout(set = 0, binding = BINDING_SPLAT_COUNT, std430) readonly buffer Counts { uint b_count[]; };
layout(set = 0, binding = BINDING_SPLAT_OFFSETS, std430) writeonly buffer Offsets { uint b_offsets[]; };

shared uint s_scan[256];

void main() {
  uint t = gl_LocalInvocationID.x;
  uint n = u_frame.width * u_frame.height * u_restir.layers;  // the domain keys (restir/domain.h)
  uint carry = 0u;
  for (uint base = 0u; base < n; base += 256u) {
    uint c = base + t < n ? b_count[base + t] : 0u;
    s_scan[t] = c;
    barrier();
    for (uint d = 1u; d < 256u; d <<= 1u) {
      uint add = t >= d ? s_scan[t - d] : 0u;
      barrier();
      s_scan[t] += add;
      barrier();
    }
    if (base + t < n) b_offsets[base + t] = carry + s_scan[t] - c;  // exclusive
    carry += s_scan[255];
    barrier();
  }
  if (t == 0u) b_offsets[n] = carry;
}
