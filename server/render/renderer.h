#pragma once
// The Renderer records one frame of a method's passes for one scene and reads back the image and
// the frame statistics. Passes a method or scene does not need are not recorded and get no memory.
#include <algorithm>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/timer.h"
#include "image/image.h"
#include "render/frame_stats.h"
#include "render/restir/domain_map.h"
#include "render/method.h"
#include "restir/restir_limits.h"
#include "render/method_table.h"
#include "render/restir/restir_options.h"
#include "render/scene_gpu.h"

namespace strata::render {

// Limits that every caller (CLI, service) is held to; violations throw std::invalid_argument
// naming the field and the limit.
struct RenderLimits {
  static constexpr uint32_t max_dimension = 8192;
  static constexpr uint64_t max_pixels = 16ull << 20;
  static constexpr uint32_t max_spp = 1u << 20;
  static constexpr uint32_t max_depth = 256;
};

struct RenderSettings {
  uint32_t width = 256;
  uint32_t height = 256;
  std::string method = "pt";
  uint32_t spp = 1;                     // samples per pixel per frame
  uint32_t max_depth = 16;              // path segments after the camera
  uint32_t seed = 0;
  uint32_t samples_per_dispatch = 16;   // a frame's samples are split into dispatches of this many
  RestirOptions restir;
  void validate() const;
};

struct FrameResult {
  image::Image image;  // mean radiance per pixel over every sample accumulated so far
  FrameStats stats;
  uint64_t accumulated_spp = 0;
  std::optional<DomainMap> domain_map;  // filled by whoever asks Renderer::domain_map (the DOMAIN_MAP encoding)
};

class Renderer {
 public:
  Renderer(const gpu::Context& ctx, const scene::Scene& scene, RenderSettings settings);
  ~Renderer();

  // Renders `frame` (its state, and `frame_index` for the random streams). With accumulate, the
  // samples add to those of previous calls instead of replacing them (reference rendering of
  // one frame state); the caller keeps the frame state unchanged while accumulating.
  FrameResult render(const scene::FrameState& frame, uint32_t frame_index, bool accumulate = false);

  // While held, frames render as if they had no previous frame (the history passes, e.g. the
  // temporal pass, do not run and each frame's reservoirs start afresh): a progressive start holds
  // them until their pipelines are compiled (service/warm_up.h). Releasing it needs no reset: the
  // previous frame's reservoirs and scene slot are kept every frame.
  void hold_history(bool held) { history_held_ = held; }

  // The last rendered frame's domain map (restir-multilayer; none for methods without pixel layers).
  std::optional<DomainMap> domain_map() const;

  // Device memory held for this renderer, by buffer group (what FrameStats::memory_bytes reports).
  std::map<std::string, uint64_t> memory_bytes() const;

  const RenderSettings& settings() const { return settings_; }
  const GpuScene& gpu_scene() const { return *scene_; }

 private:
  const gpu::Context& ctx_;
  RenderSettings settings_;
  std::unique_ptr<GpuScene> scene_;
  gpu::Buffer constants_, counters_, accum_;
  std::unique_ptr<gpu::PassTimer> timer_;
  std::unique_ptr<Method> method_;
  uint64_t accumulated_spp_ = 0;
  bool history_held_ = false;
};

}  // namespace strata::render
