// strata_di_bench: the DI tutorial's temporal-reuse experiments (seed 002, section 6) repeated on
// `cornell` with restir-di .
//
// Configurations (all restir-di, 1 path per pixel, `--light-candidates` NEE candidates at x1):
//   ris               no temporal, no spatial reuse: per-frame RIS only (the tutorial's "no temporal")
//   temporal          unbiased temporal reuse (GRIS with the reverse-shift MIS), no spatial
//   temporal-biased   the tutorial's merge: weight p^(y_prev) W_prev min(M_prev, M_max) with its
//                     heuristic validation (normal, position, material, target ratio 0.1..10)
//   temporal+spatial  unbiased temporal and one spatial neighbour (restir-di defaults)
// Cameras: static (cornell's still camera) and moving (a small sideways pan, 2 cm and 0.2 degrees of
// yaw per frame, as the tutorial's "small camera motion").
// Metrics, as the tutorial defines them (luma = Rec. 709 Y of linear RGB):
//   accuracy   per frame, sqrt(mean over pixels (Y(x) - Y(ref))^2) against a converged pt reference
//              (max_depth 2 = the same one-bounce paths) of that frame state; mean over frames 1..F-1
//   stability  per frame, the same LumaRMSE between consecutive frames (static camera only)
//   accumulated (static only) the mean of frames 0..F-1 against the reference: RGB RMSE and the
//              luma ratio mean(Y(acc)) / mean(Y(ref))
// Each metric over every pixel ("all") and over the pixels that see no emitter ("reflected").
// Each figure is the mean over --seeds independent sequences; JSON plus a table on stdout.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "gpu/context.h"
#include "render/renderer.h"
#include "scene/scene_io.h"

namespace {

using namespace strata;

struct Args {
  uint32_t width = 256, height = 256, frames = 16, seeds = 4, ref_spp = 2048, light_candidates = 8;
  std::string out = "di_bench.json";
  std::string device;
};

struct Config {
  std::string name;
  std::function<void(render::RestirOptions&)> set;
};

double luma(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

// The pixels a metric counts: all, or those that see no emitter directly. A pixel that sees the
// light is estimated by its one camera sample (reuse resamples the light reflected at x1, never what
// x1 emits), and at the ceiling light's edge one such sample is 40x the reflected light: a few edge
// pixels then make the whole LumaRMSE and hide what reuse does everywhere else.
using Mask = std::vector<uint8_t>;  // 1: counted; empty: every pixel
enum PixelSet : size_t { k_all, k_reflected, k_pixel_sets };
constexpr const char* k_pixel_set_names[k_pixel_sets] = {"all", "reflected"};

// The mean of per_pixel(i) over the pixels that mask m counts.
template <class PerPixel>
double masked_mean(const image::Image& a, const Mask& m, PerPixel per_pixel) {
  double s = 0.0;
  size_t n = size_t(a.width) * a.height, k = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!m.empty() && !m[i]) continue;
    s += per_pixel(i);
    ++k;
  }
  return s / double(k);
}

double luma_rmse(const image::Image& a, const image::Image& b, const Mask& m) {
  return std::sqrt(masked_mean(a, m, [&](size_t i) {
    double d = luma(&a.rgba[4 * i]) - luma(&b.rgba[4 * i]);
    return d * d;
  }));
}

double rgb_rmse(const image::Image& a, const image::Image& b, const Mask& m) {
  return std::sqrt(masked_mean(a, m, [&](size_t i) {
    double s = 0.0;
    for (int c = 0; c < 3; ++c) {
      double d = double(a.rgba[4 * i + c]) - b.rgba[4 * i + c];
      s += d * d;
    }
    return s / 3.0;
  }));
}

double mean_luma(const image::Image& a, const Mask& m) {
  return masked_mean(a, m, [&](size_t i) { return luma(&a.rgba[4 * i]); });
}

// The moving camera: cornell's camera panned sideways and yawed a little more every frame.
scene::FrameState moving_state(const scene::Scene& sc, uint32_t f) {
  scene::FrameState st = sc.frame_state(0);
  st.camera.position += st.camera.orientation * glm::vec3(0.02f * float(f), 0.0f, 0.0f);
  st.camera.orientation = st.camera.orientation * glm::angleAxis(glm::radians(0.2f) * float(f), glm::vec3(0, 1, 0));
  return st;
}

std::string now_iso() {
  std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

int run(const Args& a) {
  if (a.frames < 3) throw std::invalid_argument("--frames must be at least 3");
  gpu::Context ctx({a.device, false});
  scene::Scene sc = scene::builtin_scene("cornell");
  const std::vector<Config> configs = {
      {"ris", [](render::RestirOptions& o) { o.temporal = false; o.spatial = false; }},
      {"temporal", [](render::RestirOptions& o) { o.spatial = false; }},
      {"temporal-biased", [](render::RestirOptions& o) { o.spatial = false; o.unbiased = false; }},
      {"temporal+spatial", [](render::RestirOptions&) {}},
  };
  auto settings = [&](const std::string& method, uint32_t spp, uint32_t seed, uint32_t max_depth = 2) {
    render::RenderSettings rs;
    rs.width = a.width;
    rs.height = a.height;
    rs.method = method;
    rs.spp = spp;
    rs.max_depth = max_depth;
    rs.seed = seed;
    rs.restir.light_candidates = a.light_candidates;
    return rs;
  };
  nlohmann::json doc = {{"device", ctx.device_name()}, {"date_utc", now_iso()}, {"scene", "cornell"},
                        {"width", a.width}, {"height", a.height}, {"frames", a.frames}, {"seeds", a.seeds},
                        {"reference_spp", a.ref_spp}, {"light_candidates", a.light_candidates}, {"cameras", nlohmann::json::object()}};
  std::fprintf(stderr, "device: %s\n", ctx.device_name().c_str());

  // Each metric is taken twice: over every pixel and over the pixels that see no emitter
  // (PixelSet, Mask above). The reflected figures are what reuse can change.
  for (const std::string camera : {"static", "moving"}) {
    const bool moving = camera == "moving";
    const uint32_t states = moving ? a.frames : 1u;
    auto state = [&](uint32_t f) { return moving ? moving_state(sc, f) : sc.frame_state(0); };
    // References: one per distinct frame state, accumulated by pt with the same one-bounce paths;
    // and what each pixel sees directly (pt with max_depth 1: emission at x1 only), for the mask.
    std::vector<image::Image> refs;
    std::vector<Mask> reflected_masks;
    uint64_t direct_pixels = 0;
    for (uint32_t f = 0; f < states; ++f) {
      render::Renderer r(ctx, sc, settings("pt", 64, 9001 + f));
      image::Image img;
      for (uint32_t done = 0; done < a.ref_spp; done += 64) img = r.render(state(f), 0, done > 0).image;
      refs.push_back(std::move(img));
      render::Renderer e(ctx, sc, settings("pt", 256, 7001 + f, 1));
      image::Image emitted = e.render(state(f), 0).image;
      Mask reflected(size_t(a.width) * a.height);
      for (size_t i = 0; i < reflected.size(); ++i) {
        bool sees_emitter = luma(&emitted.rgba[4 * i]) > 0.0;
        reflected[i] = sees_emitter ? 0 : 1;
        direct_pixels += sees_emitter ? 1 : 0;
      }
      reflected_masks.push_back(std::move(reflected));
    }
    auto ref_of = [&](uint32_t f) -> const image::Image& { return refs[moving ? f : 0]; };
    const Mask every_pixel;
    auto mask_of = [&](uint32_t f, size_t set) -> const Mask& {
      return set == k_reflected ? reflected_masks[moving ? f : 0] : every_pixel;
    };
    std::fprintf(stderr, "[%s] references done; %.2f%% of the pixels see an emitter\n", camera.c_str(),
                 100.0 * double(direct_pixels) / (double(states) * a.width * a.height));
    double ref_mean_luma[k_pixel_sets];  // the static reference's, for the accumulated luma ratio
    for (size_t set = 0; set < k_pixel_sets; ++set) ref_mean_luma[set] = mean_luma(ref_of(0), mask_of(0, set));

    nlohmann::json cj = nlohmann::json::object();
    for (const auto& cfg : configs) {
      {  // warm-up: lavapipe compiles each pass at its first dispatch; keep that out of the timings
        auto rs = settings("restir-di", 1, 3);
        cfg.set(rs.restir);
        render::Renderer r(ctx, sc, rs);
        for (uint32_t f = 0; f < 2; ++f) r.render(state(f), f);
      }
      struct Sums {
        double acc = 0.0, stab = 0.0, accum_rmse = 0.0, accum_luma_ratio = 0.0;
        std::vector<double> acc_by_frame;
      };
      Sums sums[k_pixel_sets];
      for (Sums& m : sums) m.acc_by_frame.assign(a.frames, 0.0);
      double ms_sum = 0.0;
      uint32_t acc_n = 0, stab_n = 0;
      for (uint32_t s = 0; s < a.seeds; ++s) {
        auto rs = settings("restir-di", 1, 17 + 101 * s);
        cfg.set(rs.restir);
        render::Renderer r(ctx, sc, rs);
        image::Image prev, sum;
        for (uint32_t f = 0; f < a.frames; ++f) {
          auto fr = r.render(state(f), f);
          for (size_t set = 0; set < k_pixel_sets; ++set) {
            double e = luma_rmse(fr.image, ref_of(f), mask_of(f, set));
            sums[set].acc_by_frame[f] += e / a.seeds;
            if (f >= 1) sums[set].acc += e;
            if (f >= 1 && !moving) sums[set].stab += luma_rmse(fr.image, prev, mask_of(f, set));
          }
          if (f >= 1) {
            ms_sum += fr.stats.gpu_ms_total;
            ++acc_n;
            if (!moving) ++stab_n;
          }
          if (sum.rgba.empty()) sum = fr.image;
          else
            for (size_t i = 0; i < sum.rgba.size(); ++i) sum.rgba[i] += fr.image.rgba[i];
          prev = std::move(fr.image);
        }
        for (float& v : sum.rgba) v /= float(a.frames);
        if (!moving)
          for (size_t set = 0; set < k_pixel_sets; ++set) {
            sums[set].accum_rmse += rgb_rmse(sum, ref_of(0), mask_of(0, set)) / a.seeds;
            sums[set].accum_luma_ratio += mean_luma(sum, mask_of(0, set)) / ref_mean_luma[set] / a.seeds;
          }
      }
      nlohmann::json j = {{"mean_gpu_ms_frames_1_to_F", ms_sum / acc_n}};
      for (size_t set = 0; set < k_pixel_sets; ++set) {
        const Sums& m = sums[set];
        const char* set_name = k_pixel_set_names[set];
        nlohmann::json js = {{"accuracy_luma_rmse_mean", m.acc / acc_n}, {"accuracy_luma_rmse_by_frame", m.acc_by_frame}};
        std::printf("%-7s %-17s %-9s accuracy LumaRMSE %.5f", camera.c_str(), cfg.name.c_str(), set_name, m.acc / acc_n);
        if (!moving) {
          js["stability_luma_rmse_mean"] = m.stab / stab_n;
          js["accumulated_rgb_rmse"] = m.accum_rmse;
          js["accumulated_luma_ratio"] = m.accum_luma_ratio;
          std::printf(" | stability %.5f | accumulated RGB RMSE %.5f luma ratio %.4f", m.stab / stab_n, m.accum_rmse,
                      m.accum_luma_ratio);
        }
        std::printf(" | %.2f ms/frame\n", ms_sum / acc_n);
        j[set_name] = js;
      }
      std::fflush(stdout);
      cj[cfg.name] = j;
    }
    doc["cameras"][camera] = cj;
    std::ofstream(a.out) << doc.dump(2) << "\n";
  }
  std::fprintf(stderr, "wrote %s\n", a.out.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  CLI::App app{"the DI tutorial's temporal-reuse experiments on cornell with restir-di"};
  app.add_option("--width", a.width)->capture_default_str();
  app.add_option("--height", a.height)->capture_default_str();
  app.add_option("--frames", a.frames)->capture_default_str();
  app.add_option("--seeds", a.seeds, "independent sequences per configuration")->capture_default_str();
  app.add_option("--ref-spp", a.ref_spp)->capture_default_str();
  app.add_option("--light-candidates", a.light_candidates, "NEE candidates at x1")->capture_default_str();
  app.add_option("--out", a.out)->capture_default_str();
  app.add_option("--device", a.device);
  CLI11_PARSE(app, argc, argv);
  try {
    return run(a);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
