// The method registry: the name a session or `stratad render` asks for, to its implementation.
#include <stdexcept>

#include "render/path_tracer.h"
#include "render/restir_gather.h"
#include "render/renderer.h"

namespace strata::render {

std::unique_ptr<Method> make_method(const RenderSettings& settings, const SharedResources& shared) {
  if (settings.method == "pt")
    return std::make_unique<PathTracer>(shared, settings.width, settings.height, settings.spp, settings.samples_per_dispatch);
  if (settings.method == "restir-gather" || settings.method == "restir-di" || settings.method == "restir-splat" ||
      settings.method == "restir-splat-backup") {
    RenderSettings s = settings;
    s.restir.direct_lighting = settings.method == "restir-di" || settings.restir.direct_lighting;
    return std::make_unique<RestirGather>(shared, s);
  }
  throw std::invalid_argument("method = '" + settings.method + "' has no implementation");
}

}  // namespace strata::render
