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
#include "options/option_flags.h"
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
  options::OptionFlags flags;  // the option table's flags that were given
};

std::string frame_name(uint32_t f) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%04u", f);
  return buf;
}

int run_render(RenderArgs a) {
  namespace fs = std::filesystem;
  options::set_options(a.flags, a.settings.restir);
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
  a->settings.method = render::k_default_method;  // restir-gather (spp must then be 1; --method pt for more)
  cmd->add_option("--method", a->settings.method, "rendering method:" + render::method_help())->capture_default_str();
  cmd->add_option("--width", a->settings.width, "image width")->capture_default_str();
  cmd->add_option("--height", a->settings.height, "image height")->capture_default_str();
  cmd->add_option("--frames", a->frames, "number of frames")->capture_default_str();
  cmd->add_option("--first-frame", a->first_frame, "first frame of the scene's animation")->capture_default_str();
  cmd->add_option("--spp", a->settings.spp, "samples per pixel per frame")->capture_default_str();
  cmd->add_option("--max-depth", a->settings.max_depth, "maximum path segments")->capture_default_str();
  cmd->add_option("--seed", a->settings.seed, "random seed")->capture_default_str();
  cmd->add_option("--out", a->out, "output directory")->capture_default_str();
  // The options of the table (options/option_table.h) but spp, max_depth and exposure, above and below.
  options::add_option_flags(cmd, a->flags, {"spp", "max_depth", "exposure"});
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
