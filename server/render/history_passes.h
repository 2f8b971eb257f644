#pragma once
// The shaders whose passes run only where a frame has a previous frame to reuse (the temporal
// reuse of every ReSTIR method): a frame without history, like a session's first or one whose
// history passes are held (Renderer::hold_history), never dispatches them. A progressive start
// (service/warm_up.h) compiles them last, so that a method renders from the moment the other
// pipelines are compiled. A shader missing here is only compiled sooner; one listed wrongly is
// compiled at its first dispatch: neither changes an image.
#include <string_view>

namespace strata::render {

inline bool history_only_shader(std::string_view shader) {
  constexpr std::string_view textured = "_textured";  // GpuScene::shader's variant of the same pass
  if (shader.ends_with(textured)) shader.remove_suffix(textured.size());
  return shader == "restir_temporal" || shader == "restir_temporal_reverse" ||  // restir-gather, restir-di
         shader == "restir_splat_project" || shader == "restir_splat_scan" ||    // the splat methods' counting sort
         shader == "restir_splat_insert" || shader == "restir_splat_resample" ||
         shader == "domain_propagate";                                           // restir-multilayer's propagated domains
}

}  // namespace strata::render
