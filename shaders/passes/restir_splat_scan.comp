#version 460
// Pass `splat_scan` (restir-splat; RS-supp 3.1 step 2): the exclusive prefix sum of the per-domain
// splat counts, offsets[j] = sum_{l<j} count[l], offsets[N] = the number of splats. One workgroup of
// 256 invocations: each sums its contiguous segment of the counts, a Hillis-Steele scan in shared
// memory turns the 256 segment sums into segment offsets, and each invocation writes its segment's
// offsets in order. 17 barriers per frame instead of a chunked scan's 18 per 256 counts: on
// lavapipe a barrier switches every invocation of the workgroup.
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
  uint per = (n + 255u) / 256u;
  uint begin = min(t * per, n);
  uint end = min(begin + per, n);
  uint sum = 0u;
  for (uint j = begin; j < end; ++j) sum += b_count[j];
  s_scan[t] = sum;
  barrier();
  for (uint d = 1u; d < 256u; d <<= 1u) {
    uint add = t >= d ? s_scan[t - d] : 0u;
    barrier();
    s_scan[t] += add;
    barrier();
  }
  uint offset = s_scan[t] - sum;  // exclusive: the counts of the segments before this one
  for (uint j = begin; j < end; ++j) {
    b_offsets[j] = offset;
    offset += b_count[j];
  }
  if (t == 255u) b_offsets[n] = s_scan[255];
}
