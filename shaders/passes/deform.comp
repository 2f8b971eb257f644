#version 460
// Pass `deform` (render/scene_deform.h): the vertices of every deforming instance in the slot being
// written, from the rest vertices: morph targets first, p = p_rest + sum_t w_t dp_t (glTF 2.0
// 3.7.2.2; normals alike), then linear blend skinning, p' = sum_j w_j S_j p with normals by the
// inverse transpose of S_j, renormalised (3.7.3). One thread per deformed vertex; scene/deform.h is
// the same computation on the host, which the tests compare against.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

#include "include/bindings.h"
#include "include/deform_data.h"
#include "include/scene_data.h"

layout(set = 0, binding = BINDING_VERTICES, std430) buffer Vertices { GpuVertex b_vertices[]; };
layout(set = 0, binding = BINDING_DEFORM_JOBS, std430) readonly buffer Jobs { GpuDeformJob b_jobs[]; };
layout(set = 0, binding = BINDING_DEFORM_VERTEX_JOB, std430) readonly buffer VertexJob { uvec2 b_vertex_job[]; };
layout(set = 0, binding = BINDING_MORPH_DELTAS, std430) readonly buffer MorphDeltas { GpuMorphDelta b_morph[]; };
layout(set = 0, binding = BINDING_SKIN_VERTICES, std430) readonly buffer SkinVertices { GpuSkinVertex b_skin[]; };
layout(set = 0, binding = BINDING_SKIN_MATRICES, std430) readonly buffer SkinMatrices { GpuSkinMatrix b_matrices[]; };
layout(set = 0, binding = BINDING_MORPH_WEIGHTS, std430) readonly buffer MorphWeights { float b_weights[]; };

layout(push_constant) uniform Push { uint vertex_count; } u_push;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_push.vertex_count) return;
  uvec2 jv = b_vertex_job[i];  // (job, vertex within its primitive)
  GpuDeformJob job = b_jobs[jv.x];
  uint v = jv.y;
  vec4 rest_p = b_vertices[job.src_vertex + v].position_u;
  vec4 rest_n = b_vertices[job.src_vertex + v].normal_v;
  vec3 p = rest_p.xyz;
  vec3 n = rest_n.xyz;
  for (uint t = 0u; t < job.target_count; ++t) {
    float w = b_weights[job.weight_offset + t];
    if (w == 0.0) continue;
    uint d = job.morph_offset + t * job.vertex_count + v;
    p += w * b_morph[d].position.xyz;
    n += w * b_morph[d].normal.xyz;
  }
  if (job.skin_offset != DEFORM_NOT_SKINNED) {
    uvec4 joints = b_skin[job.skin_offset + v].joints;
    vec4 weights = b_skin[job.skin_offset + v].weights;
    vec3 ps = vec3(0.0);
    vec3 ns = vec3(0.0);
    for (int k = 0; k < 4; ++k) {
      if (weights[k] == 0.0) continue;
      uint m = job.joint_offset + joints[k];
      ps += weights[k] * (b_matrices[m].position * vec4(p, 1.0)).xyz;
      ns += weights[k] * (mat3(b_matrices[m].normal) * n);
    }
    p = ps;
    n = ns;
  }
  float len = length(n);
  n = len > 0.0 && !isinf(len) ? n / len : rest_n.xyz;
  // A non-finite position (a broken pose) would poison the BLAS: the rest position stands in.
  if (any(isnan(p)) || any(isinf(p))) p = rest_p.xyz;
  b_vertices[job.dst_vertex + v].position_u = vec4(p, rest_p.w);
  b_vertices[job.dst_vertex + v].normal_v = vec4(n, rest_n.w);
}
