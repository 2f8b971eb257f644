#pragma once
// Method `pt`: the reference path tracer (pass `path_trace`), specialised per frame for what the
// scene and camera need (thin lens, environment NEE, emitter NEE).
#include "render/method.h"

namespace strata::render {

class PathTracer : public Method {
 public:
  PathTracer(const SharedResources& shared, uint32_t width, uint32_t height, uint32_t spp, uint32_t samples_per_dispatch);
  ~PathTracer() override;
  uint32_t timed_passes() const override { return 1; }
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer, const MethodFrame& f) override;
  std::vector<PassDecision> decisions() const override;
  std::map<std::string, uint64_t> memory_bytes() const override { return {}; }

 private:
  struct Variant;
  const SharedResources shared_;
  uint32_t width_, height_, spp_, samples_per_dispatch_;
  std::map<uint32_t, std::unique_ptr<Variant>> variants_;  // by specialization key
  std::string last_variant_;
};

}  // namespace strata::render
