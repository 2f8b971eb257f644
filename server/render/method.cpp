// Method construction from the method table's row: `pt` is the path tracer, every reuse method
// is a RestirMethod composing the row's stages.
#include "render/method_table.h"
#include "render/path_tracer.h"
#include "render/renderer.h"
#include "render/restir/restir_method.h"

namespace strata::render {

std::unique_ptr<Method> make_method(const RenderSettings& settings, const SharedResources& shared) {
  const MethodSpec& spec = method_spec(settings.method);
  if (!spec.reuse)
    return std::make_unique<PathTracer>(shared, settings.width, settings.height, settings.spp, settings.samples_per_dispatch);
  return std::make_unique<RestirMethod>(shared, settings, spec);
}

}  // namespace strata::render
