// `stratad render`: renders a scene's default animation in-process (no network) and writes EXR +
// PNG per frame and frames.json with per-pass GPU milliseconds and counters for each frame; with
// --domain-map also restir-multilayer's domain map per frame (the coverage dashboard's image).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "gpu/context.h"
#include "image/image.h"
#include "render/method_table.h"
#include "render/renderer.h"
#include "scene/environment_map.h"
#include "scene/scene_io.h"
#include "scene/unrendered.h"

namespace strata::cli {
namespace {

struct RenderArgs {
  std::string scene = "cornell";
  std::string out = "out/render";
  std::string device;
  uint32_t frames = 1;
  uint32_t first_frame = 0;
  bool accumulate = false;
  float exposure = 0.0f;
  bool validation = false;
  bool domain_map = false;
  std::string environment;  // equirectangular .hdr / .exr; empty: the scene's own environment
  scene::EnvironmentOptions environment_options;
  render::RenderSettings settings;
};

std::string frame_name(uint32_t f) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%04u", f);
  return buf;
}

int run_render(const RenderArgs& a) {
  namespace fs = std::filesystem;
  a.settings.validate();
  if (a.domain_map && !render::method_spec(a.settings.method).layers)
    throw std::invalid_argument("--domain-map: method " + a.settings.method + " keeps no pixel layers (restir-multilayer does)");
  scene::Scene scene = scene::load_scene(a.scene);
  if (!a.environment.empty()) scene.environment.map = scene::load_environment_map(a.environment, a.environment_options);
  const std::vector<std::string> unrendered = scene::unrendered_features(scene);
  for (const std::string& feature : unrendered) std::fprintf(stderr, "not rendered: %s\n", feature.c_str());
  gpu::Context ctx({a.device, a.validation});
  render::Renderer renderer(ctx, scene, a.settings);
  fs::create_directories(a.out);

  nlohmann::json doc;
  doc["scene"] = scene.name;
  doc["method"] = a.settings.method;
  doc["device"] = ctx.device_name();
  doc["ignored"] = unrendered;
  doc["settings"] = {{"width", a.settings.width}, {"height", a.settings.height}, {"spp", a.settings.spp},
                     {"max_depth", a.settings.max_depth}, {"seed", a.settings.seed}, {"accumulate", a.accumulate}};
  doc["frames"] = nlohmann::json::array();
  auto t0 = std::chrono::steady_clock::now();
  for (uint32_t i = 0; i < a.frames; ++i) {
    uint32_t f = a.accumulate ? a.first_frame : a.first_frame + i;
    render::FrameResult r = renderer.render(scene.frame_state(f), a.accumulate ? i : f, a.accumulate && i > 0);
    bool last = i + 1 == a.frames;
    if (!a.accumulate || last) {
      std::string base = (fs::path(a.out) / frame_name(f)).string();
      image::write_exr(base + ".exr", r.image);
      image::write_png_preview(base + ".png", r.image, a.exposure);
    }
    nlohmann::json j = render::to_json(r.stats);
    if (a.domain_map) {
      const std::string name = frame_name(f) + "_domains.png";  // as `strata stream --encodings domain` names it
      const render::DomainMap m = renderer.domain_map().value();
      image::write_png_rgb8(fs::path(a.out) / name, render::domain_map_rgb(m), m.width, m.height);
      j["files"] = {{"domain_map", name}};
    }
    j["scene_frame"] = f;
    j["accumulated_spp"] = r.accumulated_spp;
    doc["frames"].push_back(j);
    double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "frame %u/%u  gpu %.1f ms  rays %llu  wall %.1f s\n", i + 1, a.frames, r.stats.gpu_ms_total,
                 static_cast<unsigned long long>(r.stats.rays_total()), wall);
  }
  std::ofstream(fs::path(a.out) / "frames.json") << doc.dump(2) << "\n";
  std::cout << "wrote " << a.frames << " frame(s) of '" << scene.name << "' to " << a.out << "\n";
  return 0;
}

}  // namespace

Runner add_render_command(CLI::App& app) {
  auto a = std::make_shared<RenderArgs>();
  auto* cmd = app.add_subcommand("render", "render frames in-process and write EXR, PNG and frames.json");
  cmd->add_option("--scene", a->scene, "built-in scene name or .gltf/.glb path")->capture_default_str();
  a->settings.method = render::k_default_method;  // as a session's (spp must then be 1; --method pt for more)
  cmd->add_option("--method", a->settings.method, "rendering method:" + render::method_help())->capture_default_str();
  cmd->add_option("--width", a->settings.width, "image width")->capture_default_str();
  cmd->add_option("--height", a->settings.height, "image height")->capture_default_str();
  cmd->add_option("--frames", a->frames, "number of frames")->capture_default_str();
  cmd->add_option("--first-frame", a->first_frame, "first frame of the scene's animation")->capture_default_str();
  cmd->add_option("--spp", a->settings.spp, "samples per pixel per frame")->capture_default_str();
  cmd->add_option("--max-depth", a->settings.max_depth, "maximum path segments")->capture_default_str();
  cmd->add_option("--seed", a->settings.seed, "random seed")->capture_default_str();
  cmd->add_option("--out", a->out, "output directory")->capture_default_str();
  auto& r = a->settings.restir;
  cmd->add_option("--shift", r.shift, "ReSTIR shift: reconnection | hybrid")->capture_default_str();
  cmd->add_option("--mis", r.mis, "ReSTIR spatial MIS: balance | pairwise")->capture_default_str();
  cmd->add_option("--suffix", r.suffix, "ReSTIR path suffixes when the scene changed: auto | replay | cached (biased) | fail")
      ->capture_default_str();
  cmd->add_option("--confidence-cap", r.confidence_cap,
                  "ReSTIR confidence cap of the temporal history where something moved (0: the method's, 2; restir-di 4)")
      ->capture_default_str();
  cmd->add_option("--still-confidence-cap", r.still_confidence_cap,
                  "ReSTIR: confidence cap where nothing moved, the camera and every instance (0: --confidence-cap)")
      ->capture_default_str();
  cmd->add_option("--spatial-neighbors", r.spatial_neighbors, "ReSTIR spatial neighbours (0..8)")->capture_default_str();
  cmd->add_option("--spatial-radius", r.spatial_radius, "ReSTIR spatial radius in pixels (0: 2.5% of the height, at least 4 px)")->capture_default_str();
  cmd->add_option("--initial-candidates", r.initial_candidates, "ReSTIR candidate paths per pixel")->capture_default_str();
  cmd->add_option("--light-candidates", r.light_candidates, "ReSTIR NEE samples per vertex")->capture_default_str();
  cmd->add_option("--disocclusion-spatial-neighbors", r.disocclusion_spatial_neighbors,
                  "ReSTIR spatial neighbours of pixels without history (0..8; 0: --spatial-neighbors)")
      ->capture_default_str();
  cmd->add_option("--disocclusion-initial-candidates", r.disocclusion_initial_candidates,
                  "ReSTIR splat: candidate paths of pixels no splat reached, restir-multilayer: of disoccluded ones (0..64; 0: the method's, 8 for restir-multilayer, else --initial-candidates; = --initial-candidates: off)")
      ->capture_default_str();
  cmd->add_option("--direct-strata", r.direct_strata, "ReSTIR: G x G camera samples at edges of directly seen emission (1..8)")
      ->capture_default_str();
  cmd->add_option("--albedo-strata", r.albedo_strata,
                  "ReSTIR gather: G x G camera samples of the albedo control variate at albedo edges (1..8; 1: off)")
      ->capture_default_str();
  cmd->add_option("--colour-cv", r.colour_cv,
                  "ReSTIR gather and splat: largest b of the colour control variate, the share of the way from the pixel's colour to its initial paths' (0..1; 0: off)")
      ->capture_default_str();
  cmd->add_option("--colour-cv-spread", r.colour_cv_spread,
                  "ReSTIR: k of the colour control variate's b = colour_cv k / (k + S), S the spread of the window's initial colours (0..1000; 0: b = colour_cv everywhere)")
      ->capture_default_str();
  cmd->add_option("--layers", r.layers, "restir-multilayer: pixel layers (1..8; 0: auto, from the scene's depth complexity)")
      ->capture_default_str();
  cmd->add_option("--silhouette-band", r.silhouette_band,
                  "restir-multilayer: deep domains farther than this many pixels from a front-layer silhouette are dormant (0..32; 0: off)")
      ->capture_default_str();
  cmd->add_option("--reveal-lookahead", r.reveal_lookahead,
                  "restir-multilayer: deep domains sample when predicted to be uncovered within this many frames, else dormant (0..16; 0: off)")
      ->capture_default_str();
  cmd->add_option("--deep-backup", r.deep_backup,
                  "restir-multilayer: a disoccluded pixel takes the previous deep domain that held its hit as a backup sample (true | false)")
      ->capture_default_str();
  cmd->add_option("--hole-fill-radius", r.hole_fill_radius, "restir-multilayer: hole filling radius in pixels (0..8; 0: off)")
      ->capture_default_str();
  cmd->add_option("--layer-mode", r.layer_mode, "restir-multilayer: active | uniform | no-depth-ranges (ML validation variants)")
      ->capture_default_str();
  cmd->add_option("--view-layer", r.view_layer,
                  "restir-multilayer: write layer i's domain estimates instead of the image (0: the image; 0 where inactive)")
      ->capture_default_str();
  cmd->add_option("--lod-mapping", r.lod_mapping, "ReSTIR: auto | off | uv (LoD-aware reuse, the LOD paper's vertex mapping)")
      ->capture_default_str();
  cmd->add_option("--lod-matching", r.lod_matching, "ReSTIR, --lod-mapping uv: greedy matching of UVs several points share (LOD Alg. 1)")
      ->capture_default_str();
  cmd->add_option("--lod-vertices", r.lod_vertices, "ReSTIR, --lod-mapping uv: both | primary | reconnection (LOD Fig. 5)")
      ->capture_default_str();
  cmd->add_flag("!--no-temporal-filter", r.temporal_filter, "ReSTIR gather: history from any previous pixel (no surface test)");
  cmd->add_flag("!--no-temporal", r.temporal, "ReSTIR: no temporal reuse");
  cmd->add_flag("!--no-spatial", r.spatial, "ReSTIR: no spatial reuse");
  cmd->add_flag("!--biased", r.unbiased, "ReSTIR: the DI tutorial's confidence-weighted temporal merge (biased)");
  cmd->add_option("--device", a->device, "Vulkan device name substring (default: $STRATA_DEVICE, else lavapipe)");
  cmd->add_option("--exposure", a->exposure, "PNG preview exposure in stops")->capture_default_str();
  cmd->add_flag("--accumulate", a->accumulate, "accumulate all frames into one reference image of --first-frame");
  cmd->add_flag("--validation", a->validation, "enable the Khronos validation layer");
  cmd->add_flag("--domain-map", a->domain_map,
                "restir-multilayer: also write each frame's domain map, frame_NNNN_domains.png (red: 32 x active domains, "
                "green: disoccluded, blue: covered)");
  cmd->add_option("--environment", a->environment, "equirectangular HDR environment map (Radiance .hdr or OpenEXR)");
  cmd->add_option("--environment-intensity", a->environment_options.intensity, "scales the environment map's radiance")
      ->capture_default_str();
  cmd->add_option("--environment-rotation", a->environment_options.rotation_degrees,
                  "turns the environment map about +Y, degrees counter-clockwise seen from above")
      ->capture_default_str();
  return [a] { return run_render(*a); };
}

}  // namespace strata::cli
