#include "render/reference.h"

#include <algorithm>
#include <cmath>

namespace strata::render {
namespace {

constexpr double k_relmse_epsilon = 1e-2;  // as RelMSE's denominator (client/metrics)
constexpr uint32_t k_max_batch_spp = 32;
constexpr uint32_t k_target_batches = 16;

}  // namespace

uint32_t reference_seed(uint32_t seed) {
  // murmur3's finaliser of the seed and a constant: a bijection, far from small seeds.
  uint32_t h = seed ^ 0x5EED5EEDu;
  h ^= h >> 16;
  h *= 0x85EBCA6Bu;
  h ^= h >> 13;
  h *= 0xC2B2AE35u;
  h ^= h >> 16;
  return h;
}

uint32_t reference_batch_spp(uint32_t spp) {
  const uint32_t cap = std::clamp(spp / k_target_batches, 1u, k_max_batch_spp);
  // A divisor of spp near the cap, so that the batches add up to spp exactly; else the cap (the
  // last batch rounds spp up to a whole batch).
  for (uint32_t b = cap; b >= std::max(1u, cap / 2); --b)
    if (spp % b == 0) return b;
  return cap;
}

ReferenceRender::ReferenceRender(const gpu::Context& ctx, const scene::Scene& scene, const scene::FrameState& frame,
                                 ReferenceSettings settings)
    : settings_(settings), frame_(frame) {
  batch_spp_ = reference_batch_spp(settings_.spp);
  RenderSettings rs;
  rs.width = settings_.width;
  rs.height = settings_.height;
  rs.method = "pt";
  rs.spp = batch_spp_;
  rs.max_depth = settings_.max_depth;
  rs.seed = reference_seed(settings_.seed);
  renderer_ = std::make_unique<Renderer>(ctx, scene, rs);
  sum_sq_.assign(size_t(settings_.width) * settings_.height * 3, 0.0);
}

ReferenceRender::~ReferenceRender() = default;

bool ReferenceRender::done() const { return reached_ || spp_done_ >= settings_.spp; }

void ReferenceRender::render_batch() {
  if (done()) return;
  FrameResult r = renderer_->render(frame_, k_reference_frame_index, /*accumulate=*/batches_ > 0);
  const double n_before = spp_done_, s = batch_spp_, n_after = double(r.accumulated_spp);
  const size_t pixels = size_t(settings_.width) * settings_.height;
  // The batch's own mean from the accumulated means before and after it.
  for (size_t p = 0; p < pixels; ++p)
    for (size_t c = 0; c < 3; ++c) {
      const double before = batches_ ? double(mean_.rgba[4 * p + c]) : 0.0;
      const double batch = (double(r.image.rgba[4 * p + c]) * n_after - before * n_before) / s;
      sum_sq_[3 * p + c] += s * batch * batch;
    }
  mean_ = std::move(r.image);
  spp_done_ = uint32_t(r.accumulated_spp);
  ++batches_;
  gpu_ms_ += r.stats.gpu_ms_total;

  // Var[mean] per pixel and channel from the spread of the batch means (weighted by their spp):
  // sigma^2 ~ (sum_k s_k B_k^2 - N M^2) / (K - 1), Var[M] = sigma^2 / N.
  if (batches_ >= 2) {
    const double n = n_after, k = batches_;
    double sum = 0.0;
    for (size_t p = 0; p < pixels; ++p)
      for (size_t c = 0; c < 3; ++c) {
        const double m = mean_.rgba[4 * p + c];
        const double spread = std::max(0.0, sum_sq_[3 * p + c] - n * m * m);
        sum += spread / ((k - 1.0) * n) / (m * m + k_relmse_epsilon);
      }
    relative_error_ = std::sqrt(sum / double(pixels * 3));
  }
  if (settings_.relative_error > 0.0 && batches_ >= k_min_batches_for_stop && relative_error_ <= settings_.relative_error &&
      spp_done_ < settings_.spp)
    reached_ = true;
}

ReferenceEntry ReferenceRender::result() const {
  ReferenceEntry e;
  e.image = mean_;
  e.spp = spp_done_;
  e.batches = batches_;
  e.relative_error = relative_error_;
  e.relative_error_reached = reached_;
  e.gpu_ms = gpu_ms_;
  return e;
}

}  // namespace strata::render
