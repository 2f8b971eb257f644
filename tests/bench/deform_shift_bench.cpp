// strata_deform_shift_bench: how often temporal shifts succeed on a deforming surface against the
// same surface moved rigidly. The characters scene's flag seen close up (it fills most of the
// image), animated two ways: skinned, as the scene has it (each joint past the first turns about
// the pole's axis, a wave running along the cloth), and rigid (the skin removed, the whole cloth
// turning about the pole by its middle joint's angle, the same amplitude and frequency). restir-gather
// renders F frames of each; the share of temporal shifts that succeed is 1 - (failed / attempted)
// from the frames' counters (temporal.shifts, shift_failures temporal.*), frames 1..F-1.
// Prints both shares and their ratio and writes JSON.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "gpu/context.h"
#include "render/renderer.h"
#include "scene/builtin/common.h"
#include "scene/scene_io.h"

namespace {

using namespace strata;

scene::Scene close_up(bool rigid) {
  scene::Scene s = scene::builtin_scene("characters");
  s.animation.camera.clear();
  s.camera.position = {-0.05f, 1.35f, 0.75f};
  s.camera.orientation = scene::builtin::look_at(s.camera.position, {-0.05f, 1.35f, -0.25f});
  if (rigid) {
    for (size_t i = 0; i < s.instances.size(); ++i) {
      scene::Instance& inst = s.instances[i];
      if (inst.skin < 0) continue;
      inst.skin = -1;
      for (auto& p : s.meshes[inst.lod_meshes.front()].primitives) {
        p.joints.clear();
        p.weights.clear();
      }
      // About the pole (x = -0.55, z = -0.25) by the middle joint's angle.
      scene::InstanceTrack track{uint32_t(i), {}};
      for (uint32_t f = 0; f < scene::builtin::kFrameCount; ++f) {
        const float t = scene::builtin::key_time(f);
        const float angle = 0.35f * std::sin(2.0f * 3.14159265f * 0.8f * t - 0.9f * 2.0f);
        const glm::vec3 pivot(-0.55f, 0.0f, -0.25f);
        scene::TransformKey key;
        key.time = t;
        key.rotation = glm::angleAxis(angle, glm::vec3(0, 1, 0));
        key.translation = pivot - key.rotation * pivot;
        track.keys.push_back(key);
      }
      inst.transform = scene::builtin::compose_key(track.keys.front());
      s.animation.tracks.push_back(track);
    }
    s.skins.clear();
    s.animation.joint_tracks.clear();
  }
  s.validate();
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("strata_deform_shift_bench: temporal shift success on a skinned surface against a rigid one");
  uint32_t size = 128, frames = 16;
  std::string out = "deform_shift_bench.json", device;
  app.add_option("--size", size, "image width and height");
  app.add_option("--frames", frames, "frames per run");
  app.add_option("--out", out, "JSON output");
  app.add_option("--device", device, "Vulkan device name substring");
  CLI11_PARSE(app, argc, argv);

  gpu::ContextOptions co;
  co.device = device;
  gpu::Context ctx(co);
  nlohmann::json results;
  double share[2] = {0.0, 0.0};
  for (int rigid = 0; rigid < 2; ++rigid) {
    const scene::Scene s = close_up(rigid != 0);
    render::RenderSettings rs;
    rs.width = size;
    rs.height = size;
    rs.method = "restir-gather";
    rs.max_depth = 6;
    render::Renderer r(ctx, s, rs);
    uint64_t attempted = 0, failed = 0;
    for (uint32_t f = 0; f < frames; ++f) {
      const render::FrameResult fr = r.render(s.frame_state(f), f);
      if (f == 0) continue;
      if (auto it = fr.stats.reuse.find("temporal.shifts"); it != fr.stats.reuse.end()) attempted += it->second;
      for (const auto& [name, n] : fr.stats.shift_failures)
        if (name.rfind("temporal.", 0) == 0) failed += n;
    }
    share[rigid] = attempted > 0 ? 1.0 - double(failed) / double(attempted) : 0.0;
    const char* name = rigid ? "rigid" : "skinned";
    std::printf("%-8s temporal shifts %llu, failed %llu, succeeded %.4f\n", name, (unsigned long long)attempted,
                (unsigned long long)failed, share[rigid]);
    results[name] = {{"attempted", attempted}, {"failed", failed}, {"succeeded_share", share[rigid]}};
  }
  const double ratio = share[1] > 0.0 ? share[0] / share[1] : 0.0;
  std::printf("skinned / rigid %.4f\n", ratio);
  results["skinned_over_rigid"] = ratio;
  std::ofstream(out) << nlohmann::json{{"device", ctx.device_name()}, {"size", size}, {"frames", frames}, {"results", results}}.dump(2)
                     << "\n";
  return 0;
}
