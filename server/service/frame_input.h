#pragma once
// A FrameInput checked against the session's scene and the server's limits, and the merge of
// inputs that arrive while a frame renders (latest input wins; deltas are kept).
#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "service/config.h"
#include "service/input_checks.h"
#include "strata/v1/render.pb.h"

namespace strata::service {

struct PendingInput {
  uint64_t sequence = 0;
  std::optional<uint32_t> animation_frame;     // the whole state from the default animation, first
  std::optional<scene::Camera> camera;
  std::map<uint32_t, glm::mat4> transforms;     // by instance id
  std::map<uint32_t, uint32_t> lods;            // by instance id
  std::map<uint32_t, glm::mat4> lights;         // light to world, by light id
  std::map<uint32_t, std::map<uint32_t, glm::mat4>> joints;  // joint to world, by instance id and joint
  std::map<uint32_t, std::vector<float>> morph_weights;      // by instance id
  v1::RenderOptions options;                    // only the fields that change
  std::optional<std::pair<uint32_t, uint32_t>> resolution;
  std::vector<v1::ImageEncoding> encodings;     // empty: unchanged
  std::chrono::steady_clock::time_point received;
  uint64_t coalesced = 0;                       // earlier inputs merged into this one

  // Folds a newer input into this one, as if both had been applied in order.
  void merge_newer(PendingInput&& newer);
};

// Throws ServiceError (INVALID_ARGUMENT) naming the field: values out of range, unknown instance
// ids, LoD levels a instance does not have, options and resolutions over the limits.
PendingInput parse_frame_input(const ::strata::v1::FrameInput& in, const scene::Scene& scene, const ServiceLimits& limits);

}  // namespace strata::service
