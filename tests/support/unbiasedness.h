#pragma once
// The statistical test that every ReSTIR method must pass the mean over many
// independent runs (fresh seeds) of a method matches a converged reference.
//
// Per block of B x B pixels, each run gives the block's mean radiance; over R runs these are
// independent and identically distributed, so their mean is normal to good accuracy with a standard
// error estimated from the runs. The reference has its own standard error (it is a finite render
// too). With K blocks tested, each two-sided z-score is compared against the Bonferroni threshold
// for a family-wise false-failure probability alpha: z_crit = Phi^-1(1 - alpha / (2K)). The whole
// image's mean gives one more z-test of the relative bias.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "image/image.h"

namespace strata::test {

// Per-pixel sums over independent runs of one method of a per-pixel statistic: channels . rgb
// (default r + g + b, luminance-free: all three channels; a chromatic one such as r - g tests
// colour alone).
class RunningImage {
 public:
  RunningImage(uint32_t width, uint32_t height, glm::vec3 channels = glm::vec3(1.0f));
  void add(const image::Image& run);
  uint32_t runs() const { return runs_; }
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  // Mean over runs and the standard error of that mean, for the block at (bx, by) of size block.
  void block_statistics(uint32_t bx, uint32_t by, uint32_t block, double& mean, double& std_error) const;

 private:
  uint32_t width_, height_, runs_ = 0;
  glm::vec3 channels_;
  // Per run, each pixel's statistic — kept so blocks of any size can be formed.
  std::vector<std::vector<float>> pixel_values_;
};

struct BiasReport {
  uint32_t blocks = 0;
  double z_threshold = 0.0;       // Bonferroni threshold for the blocks
  double max_abs_block_z = 0.0;
  uint32_t worst_block_x = 0, worst_block_y = 0;
  double method_mean = 0.0, reference_mean = 0.0;
  double image_z = 0.0;           // z-score of the whole-image mean difference
  double relative_bias = 0.0;     // (method - reference) / reference over the image
  // Mean over blocks of the reference's share of the z-score's variance, se_ref^2 / (se_method^2 +
  // se_ref^2): how much a finer reference would sharpen the test (0.1: its z-scores by 5%).
  double reference_share = 0.0;
  bool passed = false;
  std::string describe() const;
};

// family_alpha: probability that an unbiased method fails the test (all blocks and the image).
BiasReport compare_to_reference(const RunningImage& method, const RunningImage& reference, uint32_t block,
                                double family_alpha = 1e-4);

// Phi^-1(p) for p in (0, 1), by bisection on erfc (accurate to 1e-10).
double inverse_normal_cdf(double p);

}  // namespace strata::test
