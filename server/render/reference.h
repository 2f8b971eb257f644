#pragma once
// A converged `pt` reference of one frame state, rendered by accumulation in batches .
// The samples are those of Renderer::render(accumulate) with one frame state, so the image does
// not depend on how the samples are split into batches; the spread of the batch means gives the
// estimate of the image's relative standard error that the early stop uses.
#include <cstdint>
#include <memory>
#include <vector>

#include "gpu/context.h"
#include "render/reference_cache.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace strata::render {

struct ReferenceSettings {
  uint32_t width = 0, height = 0;
  uint32_t max_depth = 16;
  uint32_t seed = 0;              // the client's seed; the random streams use reference_seed(seed)
  uint32_t spp = 1;               // target samples per pixel
  double relative_error = 0.0;    // 0: none; else stop once the estimate is at most this
};

// The seed of a reference's random streams: a hash of the client's seed, so that a reference's
// samples are not those of a session with the same seed (which would hide that session's error).
uint32_t reference_seed(uint32_t seed);
// Frame index of the reference's random streams (one frame state; sessions count from 0).
constexpr uint32_t k_reference_frame_index = 0xFFFFFFFFu;
// The early stop is not trusted before this many batches.
constexpr uint32_t k_min_batches_for_stop = 8;
// Samples per pixel of one batch: about 16 batches, 1..32 samples each.
uint32_t reference_batch_spp(uint32_t spp);

class ReferenceRender {
 public:
  // Uploads the scene and creates the path tracer; `scene` must outlive this object.
  ReferenceRender(const gpu::Context& ctx, const scene::Scene& scene, const scene::FrameState& frame, ReferenceSettings settings);
  ~ReferenceRender();

  bool done() const;
  // Renders one batch (GPU work, then the read-back) and updates the estimate.
  void render_batch();
  // The image and statistics so far.
  ReferenceEntry result() const;

  uint32_t spp_done() const { return spp_done_; }
  uint32_t batches() const { return batches_; }
  double relative_error() const { return relative_error_; }

 private:
  ReferenceSettings settings_;
  scene::FrameState frame_;
  std::unique_ptr<Renderer> renderer_;
  uint32_t batch_spp_ = 1, spp_done_ = 0, batches_ = 0;
  double gpu_ms_ = 0.0, relative_error_ = 0.0;
  bool reached_ = false;
  image::Image mean_;               // the accumulated mean so far
  std::vector<double> sum_sq_;      // per pixel and RGB: sum over batches of spp_k * mean_k^2
};

}  // namespace strata::render
