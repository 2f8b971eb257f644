// Deforming meshes on the device (render/scene_deform.h; pass deform.comp): per deforming instance
// and scene slot a copy of its mesh's vertices, which the deformation pass writes every frame from
// the rest vertices, the morph targets and the skin (glTF 2.0 3.7.2.2 and 3.7.3), before that
// copy's BLAS is refit.
#ifndef STRATA_DEFORM_DATA_H
#define STRATA_DEFORM_DATA_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

CONST_DEF uint DEFORM_NOT_SKINNED = 0xFFFFFFFFu;

// One primitive of one deforming instance, in one slot.
struct GpuDeformJob {
  uint src_vertex;     // its rest vertices in the vertex buffer
  uint dst_vertex;     // the slot's copy
  uint vertex_count;
  uint morph_offset;   // target t, vertex v: morph deltas[morph_offset + t * vertex_count + v]
  uint target_count;
  uint weight_offset;  // the instance's morph weights of the frame: weights[weight_offset + t]
  uint skin_offset;    // vertex v's joints and weights: skin vertices[skin_offset + v] (DEFORM_NOT_SKINNED: none)
  uint joint_offset;   // the instance's skinning matrices of the frame: matrices[joint_offset + j]
};

// A morph target's displacement of one vertex (w unused).
struct GpuMorphDelta {
  vec4 position;
  vec4 normal;
};

// JOINTS_0 and WEIGHTS_0 of one vertex (weights sum to 1).
struct GpuSkinVertex {
  uvec4 joints;
  vec4 weights;
};

// Joint j of an instance at the frame: S_j = inverse(T) J_j B_j (scene/scene.h, Skin) and the
// inverse transpose of its 3 x 3 part (columns xyz of `normal`), computed on the host in double.
struct GpuSkinMatrix {
  mat4 position;
  mat4 normal;
};

STRATA_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(strata::gpu::GpuDeformJob) == 32);
static_assert(sizeof(strata::gpu::GpuSkinMatrix) == 128);
#endif
#endif
