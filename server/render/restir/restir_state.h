#pragma once
// The state a ReSTIR session keeps on the device (docs/ARCHITECTURE.md, "State"): the method's
// constants, the reservoirs of every domain (work: this frame's canonical and temporal output;
// history: the final reservoirs, ping-pong, so that the previous frame's stay readable while this
// frame's are written), the contribution f(Y) of each domain's reservoir, and the visibility
// buffer of the primary stage (ping-pong too: the gather's biased validation reads the previous one).
// Every per-domain buffer is sized by the domain count: pixels x layers (restir/domain.h; one layer
// but for restir-multilayer, whose domain state is `layer_state`).
#include <cstdint>
#include <map>
#include <string>

#include "render/method.h"
#include "render/method_table.h"
#include "render/pass.h"
#include "render/renderer.h"

namespace strata::render {

struct RestirState {
  RestirState(const SharedResources& shared, const RenderSettings& settings, const MethodSpec& spec);
  RestirState(const RestirState&) = delete;
  RestirState& operator=(const RestirState&) = delete;

  const SharedResources shared;
  const RenderSettings settings;
  const MethodSpec& spec;
  uint32_t width, height;
  uint32_t layers;            // k pixel layers (restir-multilayer; 1 for every other method)
  std::string layers_reason;  // how k was chosen (the session's `layers` decision)
  uint64_t pixels;            // width * height
  uint64_t domains;           // pixels * layers (restir/domain.h)
  bool primary_stage;         // the primary stage runs: fixed primary vertices, or a temporal or spatial stage reads it

  gpu::Buffer constants;      // GpuRestirConstants (uniform)
  gpu::Buffer work;           // per domain: canonical, then temporal output
  PingPong history;           // per domain: the frame's final reservoirs
  gpu::Buffer contribution;   // per domain f(Y) of its reservoir, then per pixel the directly seen emission
  PingPong visibility;        // per domain: the primary stage's hit (layer 0) and the representative hits of the
                              // deeper layers (GpuPrimaryHit); one entry when no primary stage runs
  // Fixed primary vertices in a textured scene: per pixel the material of its visibility-buffer entry
  // (GpuPrimaryMaterial), which the initial stage and every shift into the domain read instead of
  // filtering its textures again; one entry otherwise (every ReSTIR pass's layout has the binding).
  PingPong primary_material;
  bool primary_material_kept() const { return primary_stage && spec.fixed_primary && shared.scene.textured(); }
  // Splat methods: the splat counting sort's exclusive prefix sum over domains (domains + 1 entries;
  // stage temporal-splat writes it before the initial stage, which reads it: pixels no splat reached
  // take disocclusion_initial_candidates); one entry for the other methods.
  gpu::Buffer splat_offsets;
  // Pixel-layer domains (restir/layer_data.h; stage domain_init). Every splat method binds them (one
  // entry each but for restir-multilayer with k > 1 layers).
  PingPong domain_ranges;     // per domain: depth range, flags, occluder (GpuDomainRange)
  gpu::Buffer domain_marks;   // per domain: occluders of the representative hits propagated into it (GpuDomainMark)
  PingPong domain_list;       // the active deep domains, compacted (the previous frame's: what propagates and splats)
  PingPong domain_args;       // GpuDomainArgs: the list dispatch's workgroups and the list's length
  bool multilayer() const { return layers > 1; }
  // The splat stage's counting sort runs (a splat method with temporal reuse).
  bool splat_sort() const { return spec.temporal == StageKind::temporal_splat && settings.restir.temporal; }
  // layer_mode uniform / no-depth-ranges: deep domains by rank, a splat's layer by walking its camera ray.
  bool layer_stepping() const { return multilayer() && settings.restir.layer_mode != LayerMode::active; }
  // The silhouette band (domain_fill.comp) in pixels: layer_mode active only (0: off).
  uint32_t silhouette_band() const { return multilayer() && !layer_stepping() ? settings.restir.silhouette_band : 0; }
  // The reveal prediction (domain_build.comp) in frames: layer_mode active only (0: off).
  uint32_t reveal_lookahead() const { return multilayer() && !layer_stepping() ? settings.restir.reveal_lookahead : 0; }
  // Deep domains can be dormant (tracked, not sampled): the silhouette band or the reveal prediction.
  bool dormancy() const { return silhouette_band() > 0 || reveal_lookahead() > 0; }
  // The deep backup (restir_splat_resample.comp): layer_mode active, with temporal reuse.
  bool deep_backup() const { return multilayer() && !layer_stepping() && splat_sort() && settings.restir.deep_backup; }

  std::map<std::string, uint64_t> memory_bytes() const;
};

// What every ReSTIR pass binds (shaders/restir/restir_pass.glsl): frame and method constants,
// counters, the reservoirs it writes at `out`, the contribution buffer, both frames' primary
// materials; then `extra`.
std::vector<PassResource> restir_resources(const RestirState& state, PassResource out, std::vector<PassResource> extra = {});

}  // namespace strata::render
