#include "service/errors.h"

#include "gpu/context.h"
#include "image/image.h"
#include "scene/scene.h"

namespace strata::service {

grpc::Status status_from_exception(const std::exception& e) {
  if (const auto* s = dynamic_cast<const ServiceError*>(&e)) return {s->code, s->what()};
  if (dynamic_cast<const scene::SceneError*>(&e) || dynamic_cast<const image::ImageError*>(&e) ||
      dynamic_cast<const std::invalid_argument*>(&e))
    return {grpc::StatusCode::INVALID_ARGUMENT, e.what()};
  if (dynamic_cast<const gpu::GpuError*>(&e)) return {grpc::StatusCode::INTERNAL, std::string("device error: ") + e.what()};
  if (dynamic_cast<const std::bad_alloc*>(&e)) return {grpc::StatusCode::RESOURCE_EXHAUSTED, "out of host memory"};
  return {grpc::StatusCode::INTERNAL, e.what()};
}

}  // namespace strata::service
