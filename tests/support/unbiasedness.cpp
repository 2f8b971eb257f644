#include "support/unbiasedness.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace strata::test {

RunningImage::RunningImage(uint32_t width, uint32_t height, glm::vec3 channels)
    : width_(width), height_(height), channels_(channels) {}

void RunningImage::add(const image::Image& run) {
  if (run.width != width_ || run.height != height_) throw std::invalid_argument("run has a different size");
  std::vector<float> v(size_t(width_) * height_);
  for (size_t i = 0; i < v.size(); ++i)
    v[i] = channels_.r * run.rgba[4 * i] + channels_.g * run.rgba[4 * i + 1] + channels_.b * run.rgba[4 * i + 2];
  pixel_values_.push_back(std::move(v));
  ++runs_;
}

void RunningImage::block_statistics(uint32_t bx, uint32_t by, uint32_t block, double& mean, double& std_error) const {
  double sum = 0.0, sum2 = 0.0;
  for (const auto& run : pixel_values_) {
    double b = 0.0;
    uint32_t n = 0;
    for (uint32_t y = by * block; y < std::min(height_, (by + 1) * block); ++y)
      for (uint32_t x = bx * block; x < std::min(width_, (bx + 1) * block); ++x, ++n) b += run[size_t(y) * width_ + x];
    b /= double(n);
    sum += b;
    sum2 += b * b;
  }
  double r = double(runs_);
  mean = sum / r;
  double var = runs_ > 1 ? std::max(0.0, (sum2 - r * mean * mean) / (r - 1.0)) : 0.0;
  std_error = std::sqrt(var / r);
}

double inverse_normal_cdf(double p) {
  if (!(p > 0.0 && p < 1.0)) throw std::invalid_argument("inverse_normal_cdf needs p in (0, 1)");
  double lo = -40.0, hi = 40.0;
  for (int i = 0; i < 200; ++i) {
    double mid = 0.5 * (lo + hi);
    double cdf = 0.5 * std::erfc(-mid / std::sqrt(2.0));
    (cdf < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

BiasReport compare_to_reference(const RunningImage& method, const RunningImage& reference, uint32_t block,
                                double family_alpha) {
  if (method.width() != reference.width() || method.height() != reference.height())
    throw std::invalid_argument("method and reference differ in size");
  if (method.runs() < 8 || reference.runs() < 2) throw std::invalid_argument("too few runs for a z-test");
  BiasReport r;
  uint32_t nx = (method.width() + block - 1) / block, ny = (method.height() + block - 1) / block;
  r.blocks = nx * ny;
  // K block tests plus the image test share alpha.
  r.z_threshold = inverse_normal_cdf(1.0 - family_alpha / (2.0 * double(r.blocks + 1)));
  for (uint32_t by = 0; by < ny; ++by) {
    for (uint32_t bx = 0; bx < nx; ++bx) {
      double m, ms, f, fs;
      method.block_statistics(bx, by, block, m, ms);
      reference.block_statistics(bx, by, block, f, fs);
      // A floor for the rounding of float images: a block that every run sees the same (a directly
      // seen constant sky) has no variance, and its means may differ in the last bits.
      double rounding = 1e-6 * std::max(std::abs(m), std::abs(f));
      double se = std::sqrt(ms * ms + fs * fs + rounding * rounding);
      double z = se > 0.0 ? std::abs(m - f) / se : (m == f ? 0.0 : INFINITY);
      if (se > 0.0) r.reference_share += fs * fs / (se * se) / double(r.blocks);
      if (z > r.max_abs_block_z) {
        r.max_abs_block_z = z;
        r.worst_block_x = bx;
        r.worst_block_y = by;
      }
    }
  }
  double ms, fs;
  uint32_t whole = std::max(method.width(), method.height());
  method.block_statistics(0, 0, whole, r.method_mean, ms);
  reference.block_statistics(0, 0, whole, r.reference_mean, fs);
  double se = std::sqrt(ms * ms + fs * fs);
  r.image_z = se > 0.0 ? std::abs(r.method_mean - r.reference_mean) / se : 0.0;
  r.relative_bias = r.reference_mean != 0.0 ? (r.method_mean - r.reference_mean) / r.reference_mean : 0.0;
  r.passed = r.max_abs_block_z <= r.z_threshold && r.image_z <= r.z_threshold;
  return r;
}

std::string BiasReport::describe() const {
  std::ostringstream os;
  os << "blocks " << blocks << ", max |z| " << max_abs_block_z << " at block (" << worst_block_x << ", " << worst_block_y
     << "), threshold " << z_threshold << "; image mean " << method_mean << " vs reference " << reference_mean
     << " (relative bias " << relative_bias << ", z " << image_z << "); reference's variance share " << reference_share;
  return os.str();
}

}  // namespace strata::test
