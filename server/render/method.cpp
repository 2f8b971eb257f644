// The method registry: the name a session or `stratad render` asks for, to its implementation.
#include <stdexcept>

#include "render/path_tracer.h"
#include "render/renderer.h"

namespace strata::render {

std::unique_ptr<Method> make_method(const RenderSettings& settings, const SharedResources& shared) {
  if (settings.method == "pt")
    return std::make_unique<PathTracer>(shared, settings.width, settings.height, settings.spp, settings.samples_per_dispatch);
  throw std::invalid_argument("method = '" + settings.method + "' has no implementation");
}

}  // namespace strata::render
