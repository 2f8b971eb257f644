#pragma once
// Which pipelines Mesa's disk cache holds, as far as this program compiled them there: a list of
// their digests in a file inside that cache's folder ($MESA_SHADER_CACHE_DIR, else
// $XDG_CACHE_HOME/mesa_shader_cache, else ~/.cache/mesa_shader_cache), so that it goes when the
// cache goes. A digest covers the pipeline's key (shader, bindings, specialization constants), its
// SPIR-V and the device's name (which carries the LLVM version). The list can be wrong only the
// safe way for a start: a pipeline listed but evicted by Mesa since is compiled at its first
// dispatch, as without the list. With MESA_SHADER_CACHE_DISABLE set nothing is ever listed.
#include <string>
#include <vector>

#include "gpu/pipeline_warmup.h"

namespace strata::gpu {

// Whether every one of `pipelines` was compiled into the cache on `device_name`.
bool all_compiled(const std::vector<PipelineInfo>& pipelines, const std::string& device_name);
// Lists `pipelines` as compiled into the cache on `device_name`.
void note_compiled(const std::vector<PipelineInfo>& pipelines, const std::string& device_name);

}  // namespace strata::gpu
