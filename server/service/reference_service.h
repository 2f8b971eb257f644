#pragma once
// RenderReference: converged `pt` references of exact frame states, rendered by
// accumulation in batches that take turns with sessions' frames on the frame scheduler, and
// cached on disk (render::ReferenceCache) by a content hash of scene, frame state and settings.
#include <atomic>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include <grpcpp/grpcpp.h>

#include "render/reference_cache.h"
#include "scene/scene.h"
#include "service/service_core.h"
#include "strata/v1/render.pb.h"

namespace strata::service {

// Resolves a FrameState message against `scene`: the default animation's frame, then the camera,
// transforms and LoD levels that are set. Errors are INVALID_ARGUMENT naming the field under
// `field` (e.g. "frame.camera.position.x"). camera_open is left unset (it needs the previous frame).
scene::FrameState resolve_frame_state(const v1::FrameState& state, const scene::Scene& scene, const ServiceLimits& limits,
                                      const std::string& field);

class ReferenceService {
 public:
  explicit ReferenceService(ServiceCore& core);
  ~ReferenceService();
  ReferenceService(const ReferenceService&) = delete;
  ReferenceService& operator=(const ReferenceService&) = delete;

  grpc::Status render(grpc::ServerContext* ctx, const v1::ReferenceRequest& request, v1::Reference* response);
  const render::ReferenceCache& cache() const { return cache_; }

 private:
  struct LoadedScene {
    std::shared_ptr<const scene::Scene> scene;
    std::string hash;  // render::scene_content_hash
  };
  LoadedScene load_scene(const v1::SceneSource& source);
  void respond(const v1::ReferenceRequest& request, const render::ReferenceEntry& entry, v1::Reference* response) const;

  ServiceCore& core_;
  const render::ReferenceCache cache_;
  std::mutex mu_;
  std::list<std::pair<std::string, LoadedScene>> builtins_;  // most recently used first
  std::atomic<uint32_t> in_flight_{0};
};

}  // namespace strata::service
