#include "restir/sequence_runs.h"

#include <cstdio>

#include "gpu/gpu_context.h"

namespace strata::test {
namespace {

void add_to(image::Image& sum, const image::Image& img) {
  if (sum.rgba.empty()) {
    sum = img;
    return;
  }
  for (size_t i = 0; i < sum.rgba.size(); ++i) sum.rgba[i] += img.rgba[i];
}

}  // namespace

image::Image sequence_mean(const scene::Scene& s, const SequenceRun& run, uint32_t seed, uint32_t spp) {
  render::RenderSettings rs;
  rs.width = run.size;
  rs.height = run.size;
  rs.method = run.method;
  rs.max_depth = run.max_depth;
  rs.spp = spp;
  rs.seed = seed;
  run.options(rs.restir);
  render::Renderer renderer(gpu_context(), s, rs);
  image::Image mean;
  for (uint32_t f = 0; f < run.frames; ++f) {
    auto r = renderer.render(run.state(s, f), f);
    if (f > 0) add_to(mean, r.image);  // frames 1 .. F-1 reuse history
  }
  for (float& v : mean.rgba) v /= float(run.frames - 1);
  return mean;
}

RunningImage pt_reference(const scene::Scene& s, const SequenceRun& run, uint32_t runs, uint32_t spp) {
  RunningImage out(run.size, run.size);
  for (uint32_t r = 0; r < runs; ++r) {
    render::RenderSettings rs;
    rs.width = run.size;
    rs.height = run.size;
    rs.spp = spp;
    rs.max_depth = run.max_depth;
    rs.seed = 90000 + r;
    rs.restir.light_sampler = render::LightSampler::power;  // the plain alias table, independent of the light tree
    image::Image mean;
    for (uint32_t f = 1; f < run.frames; ++f) {
      render::Renderer renderer(gpu_context(), s, rs);
      add_to(mean, renderer.render(run.state(s, f), f).image);
    }
    for (float& v : mean.rgba) v /= float(run.frames - 1);
    out.add(mean);
  }
  return out;
}

}  // namespace strata::test

namespace strata::test {

void expect_matches_pt(const scene::Scene& s, const std::string& name, const SequenceRun& run, uint32_t runs,
                       uint32_t reference_runs, uint32_t reference_spp) {
  const RunningImage ref = pt_reference(s, run, reference_runs, reference_spp);
  RunningImage method(run.size, run.size);
  for (uint32_t r = 0; r < runs; ++r) method.add(sequence_mean(s, run, 1000 + r));
  const BiasReport report = compare_to_reference(method, ref, 4);
  std::printf("%s: %s\n", name.c_str(), report.describe().c_str());
  EXPECT_TRUE(report.passed) << name << ": " << report.describe();
}

}  // namespace strata::test
