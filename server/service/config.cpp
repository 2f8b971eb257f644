#include "service/config.h"

#include <stdexcept>

#include "render/renderer.h"

namespace strata::service {
namespace {

void require_in(const char* name, uint64_t value, uint64_t lo, uint64_t hi) {
  if (value < lo || value > hi)
    throw std::invalid_argument(std::string(name) + " = " + std::to_string(value) + " is outside [" + std::to_string(lo) +
                                ", " + std::to_string(hi) + "]");
}

}  // namespace

void ServiceConfig::validate() const {
  using render::RenderLimits;
  require_in("max_sessions", limits.max_sessions, 1, 1024);
  require_in("max_dimension", limits.max_dimension, 1, RenderLimits::max_dimension);
  require_in("max_pixels", limits.max_pixels, 1, RenderLimits::max_pixels);
  require_in("max_scene_bytes", limits.max_scene_bytes, 1024, 1ull << 30);
  require_in("max_texture_bytes", limits.max_texture_bytes, 1ull << 20, 4ull << 30);  // texel offsets are 32-bit
  require_in("max_instances", limits.max_instances, 1, 1u << 20);
  require_in("max_spp", limits.max_spp, 1, RenderLimits::max_spp);
  require_in("max_depth", limits.max_depth, 1, RenderLimits::max_depth);
  require_in("max_reference_spp", limits.max_reference_spp, 1, RenderLimits::max_spp);
  require_in("max_environment_bytes", limits.max_environment_bytes, 1024, 1ull << 30);
  require_in("max_environment_dimension", limits.max_environment_dimension, 1, 16384);
  require_in("idle_timeout_ms", uint64_t(idle_timeout.count()), 10, uint64_t(24) * 3600 * 1000);
  require_in("drain_timeout_ms", uint64_t(drain_timeout.count()), 0, uint64_t(3600) * 1000);
  require_in("encode_threads", encode_threads, 1, 64);
  if (max_frame_bytes(limits.max_pixels) > uint64_t(INT32_MAX))
    throw std::invalid_argument("max_pixels = " + std::to_string(limits.max_pixels) +
                                " makes a frame larger than gRPC's 2 GiB message limit");
}

uint64_t max_frame_bytes(uint64_t pixels) { return pixels * 25 + (1ull << 20); }

}  // namespace strata::service
