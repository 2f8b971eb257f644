// LDR-FLIP (Andersson et al. 2020, "FLIP: A Difference Evaluator for Alternating Images", cited as
// FLIP20 with the section title): the colour pipeline (CSF filtering in YCxCz, Hunt-adjusted HyAB,
// error redistribution), the feature pipeline (edges and points of the achromatic channel) and
// their combination E = E_c^(1 - E_f).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "metrics/flip_colour.h"
#include "metrics/flip_internal.h"
#include "metrics/metrics.h"
#include "metrics/validate.h"

namespace strata::metrics {
namespace detail {
namespace {

struct Opponent {
  Plane y, cx, cz;
};

// FLIP20 colour pipeline: linear RGB -> XYZ -> YCxCz, per pixel.
Opponent to_ycxcz(const LinearRgb& rgb) {
  const uint32_t w = rgb.r.width, h = rgb.r.height;
  Opponent o{Plane(w, h), Plane(w, h), Plane(w, h)};
  parallel_rows(h, [&](uint32_t y) {
    for (size_t i = size_t(y) * w; i < size_t(y + 1) * w; ++i) {
      const Color3 c = linear_rgb_to_ycxcz({rgb.r.v[i], rgb.g.v[i], rgb.b.v[i]});
      o.y.v[i] = float(c[0]);
      o.cx.v[i] = float(c[1]);
      o.cz.v[i] = float(c[2]);
    }
  });
  return o;
}

// FLIP20 colour pipeline, spatial filtering: each opponent channel convolved with its CSF.
Opponent csf_filter(const Opponent& o, double ppd) {
  return {filter_csf(o.y, csf_kernel(kCsfAchromatic, ppd)), filter_csf(o.cx, csf_kernel(kCsfRedGreen, ppd)),
          filter_csf(o.cz, csf_kernel(kCsfBlueYellow, ppd))};
}

// FLIP20 feature pipeline: |edge| and |point| responses of the achromatic channel normalized to
// [0, 1] by (Y' + 16) / 116 (that is, Y / Yn), each the length of the (x, y) filter responses.
struct Features {
  Plane edge, point;
};
Features detect_features(const Plane& y_opponent, const FeatureKernels& k) {
  Plane yn(y_opponent.width, y_opponent.height);
  for (size_t i = 0; i < yn.v.size(); ++i) yn.v[i] = (y_opponent.v[i] + 16.0f) / 116.0f;
  const Plane ex = filter_separable(yn, k.d1, k.g), ey = filter_separable(yn, k.g, k.d1);
  const Plane px = filter_separable(yn, k.d2, k.g), py = filter_separable(yn, k.g, k.d2);
  Features f{Plane(yn.width, yn.height), Plane(yn.width, yn.height)};
  for (size_t i = 0; i < yn.v.size(); ++i) {  // responses are within [-1, 1]: no overflow
    f.edge.v[i] = std::sqrt(ex.v[i] * ex.v[i] + ey.v[i] * ey.v[i]);
    f.point.v[i] = std::sqrt(px.v[i] * px.v[i] + py.v[i] * py.v[i]);
  }
  return f;
}

}  // namespace

std::vector<float> ldr_flip_linear(const LinearRgb& test, const LinearRgb& reference, double pixels_per_degree) {
  const uint32_t w = reference.r.width, h = reference.r.height;
  const Opponent test_o = to_ycxcz(test), ref_o = to_ycxcz(reference);

  // Colour pipeline: filter, back to linear RGB, clamp to the unit cube, Hunt-adjusted CIELAB,
  // HyAB distance, redistribution to [0, 1] (FLIP20 colour pipeline).
  const Opponent test_f = csf_filter(test_o, pixels_per_degree), ref_f = csf_filter(ref_o, pixels_per_degree);
  std::vector<float> error(size_t(w) * h);
  parallel_rows(h, [&](uint32_t y) {
    for (size_t i = size_t(y) * w; i < size_t(y + 1) * w; ++i) {
      auto to_lab = [i](const Opponent& o) {
        Color3 rgb = ycxcz_to_linear_rgb({o.y.v[i], o.cx.v[i], o.cz.v[i]});
        for (double& c : rgb) c = std::clamp(c, 0.0, 1.0);
        return linear_rgb_to_hunt_lab(rgb);
      };
      error[i] = float(remap_colour_error(hyab(to_lab(test_f), to_lab(ref_f))));
    }
  });

  // Feature pipeline on the unfiltered achromatic channels (FLIP20 feature pipeline):
  // E_f = ( max(| |edge_r| - |edge_t| |, | |point_r| - |point_t| |) / sqrt(2) )^q_f.
  const FeatureKernels fk = feature_kernels(pixels_per_degree);
  const Features test_feat = detect_features(test_o.y, fk), ref_feat = detect_features(ref_o.y, fk);
  const double inv_sqrt2 = 1.0 / std::numbers::sqrt2;
  parallel_rows(h, [&](uint32_t y) {
    for (size_t i = size_t(y) * w; i < size_t(y + 1) * w; ++i) {
      const double edge_diff = std::abs(double(ref_feat.edge.v[i]) - test_feat.edge.v[i]);
      const double point_diff = std::abs(double(ref_feat.point.v[i]) - test_feat.point.v[i]);
      const double e_f = std::pow(std::min(1.0, inv_sqrt2 * std::max(edge_diff, point_diff)), kQf);
      // FLIP20, final error map: E = E_c^(1 - E_f).
      error[i] = float(std::pow(double(error[i]), 1.0 - e_f));
    }
  });
  return error;
}

void check_ppd(double pixels_per_degree) {
  if (!(pixels_per_degree > 0.0) || !std::isfinite(pixels_per_degree)) {
    throw MetricError("pixels_per_degree must be finite and > 0, got " + std::to_string(pixels_per_degree));
  }
}

}  // namespace detail

FlipResult ldr_flip(const image::Image& test, const image::Image& reference, Mask mask, const FlipOptions& options) {
  detail::check_ppd(options.pixels_per_degree);
  detail::check_inputs(test, reference, mask);
  const uint32_t w = reference.width, h = reference.height;
  // sRGB in [0, 1] (values outside are clamped, as the display would) -> linear RGB.
  auto linearize = [w, h](const image::Image& img) {
    detail::LinearRgb out{detail::Plane(w, h), detail::Plane(w, h), detail::Plane(w, h)};
    detail::Plane* planes[3] = {&out.r, &out.g, &out.b};
    for (size_t i = 0; i < size_t(w) * h; ++i) {
      for (int c = 0; c < 3; ++c) {
        planes[c]->v[i] = float(detail::srgb_to_linear(std::clamp(double(img.rgba[4 * i + c]), 0.0, 1.0)));
      }
    }
    return out;
  };
  FlipResult result;
  result.error_map = detail::ldr_flip_linear(linearize(test), linearize(reference), options.pixels_per_degree);
  const detail::Pooled pooled = detail::masked_mean(result.error_map, mask);
  result.mean = pooled.mean;
  result.pixels = pooled.pixels;
  return result;
}

}  // namespace strata::metrics
