#pragma once
// GpuFrameConstants for a frame: the camera in render space, the light-sampling setup, and the
// same of the previous frame with the history flags.
#include "include/frame_data.h"
#include "render/scene_gpu.h"
#include "scene/scene.h"

namespace strata::render {

struct FrameSetup {
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t frame_index = 0;
  uint32_t seed = 0;
  uint32_t spp = 1;
  uint32_t max_depth = 16;
  bool env_nee = false;  // the environment is sampled by next-event estimation
  uint32_t splats_per_frame = 1;  // restir-splat*: K over an open shutter
  bool fixed_primary = false;     // PRIMARY_DOMAIN: the primary stage traces each pixel's camera sample
  bool history_held = false;      // the history passes wait for their pipelines: the frame has no history (Renderer::hold_history)
};

// Whether next-event estimation samples the environment (docs/ARCHITECTURE.md, Light sampling):
// always for an environment map (render/scene_environment.h), with its power's share of the light
// sampler; the constant environment only where the scene has no emitters. A constant environment
// is better found by the BSDF sample every path vertex traces anyway (cosine- or lobe-shaped
// against NEE's uniform sphere, MIS-weighted by the same rules); an NEE sample spent on it is one
// not spent on the emitters, and the even split of earlier versions raised pt's RelMSE 2-5x on
// chess, foliage and carousel (docs/BENCHMARKS.md, Light selection). Escaped BSDF rays then carry
// the constant environment with MIS weight 1. A scene property: the same every frame.
bool environment_nee(const scene::Environment& env, bool scene_has_emitters);

// K time partitions of a frame (RS-main Eq. 19): splats_per_frame when the shutter is open (the
// camera moves over it), else 1. The splat stage dispatches K and the passes read the same K from
// GpuFrameConstants::time_partitions.
uint32_t time_partitions(const scene::FrameState& frame, uint32_t splats_per_frame);

// The camera at the frame's instant in its render space (at the origin), for a w x h image.
gpu::GpuCamera make_camera(const scene::Camera& cam, uint32_t width, uint32_t height);
// The camera's motion over the frame's shutter (frame.camera_open to frame.camera).
gpu::GpuShutter make_shutter(const scene::FrameState& frame);

// Call after GpuScene::record_update for the same frame (it uses that frame's emitter table, and
// the previous frame's camera and light totals that the scene kept).
gpu::GpuFrameConstants make_frame_constants(const scene::FrameState& frame, const scene::Environment& env,
                                            const GpuScene& scene, const FrameSetup& setup);

}  // namespace strata::render
