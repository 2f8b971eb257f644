#pragma once
// Sampling the default animation (see Animation in scene.h): linear for vectors, shortest-path
// slerp for rotations, clamped outside the keys. At a key's exact time the key itself is
// returned, so sampling at key times reproduces the keys bit for bit.
#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace strata::scene {

// `keys` must be non-empty and sorted by time.
CameraKey sample_camera(const std::vector<CameraKey>& keys, float time);
TransformKey sample_transform(const std::vector<TransformKey>& keys, float time);
// Morph weights: linear per weight between keys (glTF's LINEAR), clamped outside them.
std::vector<float> sample_morph(const std::vector<MorphKey>& keys, float time);

// Time in seconds of frame `frame` at `frames_per_second`.
float frame_time(uint32_t frame, float frames_per_second);

// The last key time of the animation (camera keys, tracks and LoD schedule), 0 when it has none.
float animation_duration(const Animation& animation);

}  // namespace strata::scene
