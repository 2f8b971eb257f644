#version 460
// Pass `splat_insert` (restir-splat; RS-supp 3.1 step 3, global insertion): every splat that
// landed is written into its current pixel's range of the list, offsets[j] .. offsets[j+1]. The
// counts are consumed as the slot allocator (they end at 0). A thread per splat record: previous
// pixel i and time partition n (gl_GlobalInvocationID.z); the list holds record indices.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "include/bindings.h"
#include "include/frame_data.h"
#include "restir/domain.h"
#include "restir/restir_data.h"
#include "restir/splat_data.h"

layout(set = 0, binding = BINDING_FRAME, std140) uniform Frame { GpuFrameConstants u_frame; };
layout(set = 0, binding = BINDING_RESTIR, std140) uniform Restir { GpuRestirConstants u_restir; };
layout(set = 0, binding = BINDING_SPLAT_TARGET, std430) readonly buffer Targets { uint b_target[]; };
layout(set = 0, binding = BINDING_SPLAT_COUNT, std430) buffer Counts { uint b_count[]; };
layout(set = 0, binding = BINDING_SPLAT_OFFSETS, std430) readonly buffer Offsets { uint b_offsets[]; };
layout(set = 0, binding = BINDING_SPLAT_LIST, std430) writeonly buffer List { uint b_list[]; };

void main() {
  uvec2 prev_pixel = gl_GlobalInvocationID.xy;
  if (prev_pixel.x >= u_frame.prev_width || prev_pixel.y >= u_frame.prev_height) return;
  uint layers = u_restir.layers;  // z: the previous domain's layer, then the time partition (restir_splat_project.comp)
  uint record = gl_GlobalInvocationID.z / layers * u_frame.prev_width * u_frame.prev_height * layers +
                domain_index(prev_pixel, gl_GlobalInvocationID.z % layers, u_frame.prev_width, u_frame.prev_height);
  uint j = b_target[record];
  if (j == SPLAT_NONE) return;
  uint slot = b_offsets[j] + atomicAdd(b_count[j], 0xFFFFFFFFu) - 1u;  // count - 1 .. 0
  b_list[slot] = record;
}
