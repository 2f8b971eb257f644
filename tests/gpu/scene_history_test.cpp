// The scene history of methods with temporal reuse (docs/ARCHITECTURE.md, State): after an
// update, the previous frame's TLAS and instance records are still on the device in the other slot,
// bound at BINDING_TLAS_PREV / BINDING_INSTANCES_PREV, in that frame's render space; `pt` keeps none.
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>

#include "gpu/gpu_context.h"
#include "support/test_scenes.h"
#include "include/frame_data.h"
#include "render/frame_constants.h"
#include "render/ray_probe.h"
#include "render/renderer.h"

namespace strata::test {
namespace {

class SceneHistory : public GpuTest {};

scene::Mesh unit_quad() { return quad_mesh(0.5f, 0.0f, 0); }  // [-0.5, 0.5]^2 in z = 0, facing +z

// Instance 0 moves and switches LoD level between the two states; instance 1 stays at x = -3.
scene::Scene two_quads() {
  scene::Scene s;
  s.name = "two-quads";
  s.materials.push_back({});
  s.meshes = {unit_quad(), unit_quad()};
  s.instances.push_back({"mover", {0, 1}, glm::mat4(1.0f), 0});
  s.instances.push_back({"still", {0}, glm::translate(glm::mat4(1.0f), glm::vec3(-3, 0, 0)), 0});
  return s;
}

// State 0: mover at x = 0, LoD 0, camera at (0, 0, 5). State 1: mover at x = 2, LoD 1, and the
// camera moved to (1, 0, 5), so the two slots have different render spaces too.
scene::FrameState state(const scene::Scene& s, int which) {
  scene::FrameState f;
  f.camera = s.camera;
  f.camera.position = which == 0 ? glm::vec3(0, 0, 5) : glm::vec3(1, 0, 5);
  f.transforms = {glm::translate(glm::mat4(1.0f), glm::vec3(which == 0 ? 0.0f : 2.0f, 0, 0)), s.instances[1].transform};
  f.lods = {which == 0 ? 0u : 1u, 0u};
  return f;
}

// World-space rays down -z at x = 0 (the mover in state 0), x = 2 (state 1) and x = -3 (still).
const render::ProbeRay k_rays[] = {{{0, 0, 5}, {0, 0, -1}}, {{2, 0, 5}, {0, 0, -1}}, {{-3, 0, 5}, {0, 0, -1}}};

void expect_state(const std::vector<gpu::GpuProbeHit>& h, int which, const std::string& where) {
  ASSERT_EQ(h.size(), 3u) << where;
  const auto& on_mover = h[which == 0 ? 0 : 1];
  const auto& off_mover = h[which == 0 ? 1 : 0];
  EXPECT_NEAR(on_mover.t, 5.0f, 1e-4f) << where << ": the mover is not where state " << which << " put it";
  EXPECT_EQ(on_mover.instance, 0u) << where;
  EXPECT_EQ(on_mover.lod, uint32_t(which)) << where << ": instance records of the wrong frame";
  EXPECT_LT(off_mover.t, 0.0f) << where << ": hit the mover where state " << which << " has none";
  EXPECT_NEAR(h[2].t, 5.0f, 1e-4f) << where;
  EXPECT_EQ(h[2].instance, 1u) << where;
}

TEST_F(SceneHistory, PreviousSlotHoldsThePreviousFrame) {
  scene::Scene s = two_quads();
  render::RayProbe probe(gpu_context(), s, /*keep_history=*/true);
  const render::GpuScene& gs = probe.gpu_scene();
  ASSERT_TRUE(gs.keeps_history());
  // Each step updates to a state and traces one slot; every slot is traced at both parities.
  struct Step {
    int state;
    render::ProbeSlot slot;
  };
  const Step steps[] = {{0, render::ProbeSlot::previous}, {1, render::ProbeSlot::previous}, {0, render::ProbeSlot::previous},
                        {1, render::ProbeSlot::current},  {1, render::ProbeSlot::current},  {0, render::ProbeSlot::current}};
  int prev_state = 0;
  std::vector<uint32_t> slot_lods[2];  // LoD levels each slot's TLAS was last built with
  for (size_t k = 0; k < std::size(steps); ++k) {
    const Step& st = steps[k];
    scene::FrameState frame = state(s, st.state);
    uint32_t builds = gs.tlas_builds(), refits = gs.tlas_refits();
    auto hits = probe.trace(frame, k_rays, st.slot);
    std::string where = "step " + std::to_string(k) + (st.slot == render::ProbeSlot::previous ? " previous" : " current");
    // The first frame seeds the previous slot with itself.
    expect_state(hits, st.slot == render::ProbeSlot::previous ? (k == 0 ? st.state : prev_state) : st.state, where);

    EXPECT_EQ(gs.parity(), int(k % 2)) << where;
    EXPECT_EQ(gs.history_valid(), k >= 1) << where;
    EXPECT_EQ(gs.moved_since_previous(), k >= 1 && st.state != prev_state) << where;
    EXPECT_EQ(gs.previous_frame(), state(s, k == 0 ? st.state : prev_state)) << where;
    // One TLAS update per frame; each TLAS refits only if ITS last build had the same LoD levels.
    if (k == 0) slot_lods[0] = slot_lods[1] = frame.lods;
    bool refit = k > 0 && slot_lods[k % 2] == frame.lods;
    slot_lods[k % 2] = frame.lods;
    EXPECT_EQ(gs.tlas_builds() - builds, refit ? 0u : 1u) << where;
    EXPECT_EQ(gs.tlas_refits() - refits, refit ? 1u : 0u) << where;
    prev_state = st.state;
  }
}

TEST_F(SceneHistory, FrameConstantsDescribeThePreviousFrame) {
  scene::Scene s = two_quads();
  render::GpuScene gs(gpu_context(), s, /*keep_history=*/true);
  render::FrameSetup setup{32, 16, 0, 0, 1, 4, false};
  auto update = [&](int which) {
    scene::FrameState f = state(s, which);
    gpu_context().submit_and_wait([&](VkCommandBuffer cmd) { gs.record_update(cmd, f); });
    return render::make_frame_constants(f, s.environment, gs, setup);
  };
  auto same_camera = [](const gpu::GpuCamera& a, const gpu::GpuCamera& b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  gpu::GpuFrameConstants c0 = update(0);
  EXPECT_EQ(c0.history_flags, 0u);
  EXPECT_TRUE(same_camera(c0.prev_camera, c0.camera)) << "the seeded previous slot holds the first frame";
  s.camera.orientation = glm::angleAxis(0.3f, glm::vec3(0, 1, 0));  // state 1 also turns the camera
  gpu::GpuFrameConstants c1 = update(1);
  EXPECT_EQ(c1.history_flags, gpu::HISTORY_VALID | gpu::HISTORY_SCENE_MOVED);
  EXPECT_TRUE(same_camera(c1.prev_camera, c0.camera));
  EXPECT_FALSE(same_camera(c1.camera, c0.camera));
  EXPECT_EQ(c1.prev_width, 32u);
  EXPECT_EQ(c1.prev_height, 16u);
  EXPECT_EQ(c1.prev_total_emitter_power, c0.total_emitter_power);
  EXPECT_EQ(c1.prev_env_select_prob, c0.env_select_prob);
  gpu::GpuFrameConstants c2 = update(1);  // the same state again (as when accumulating): the camera stood still
  EXPECT_EQ(c2.history_flags, gpu::HISTORY_VALID | gpu::HISTORY_CAMERA_STILL);
  EXPECT_TRUE(same_camera(c2.prev_camera, c1.camera));
}

// Per-instance change tracking: the device's instance records of a frame say which instances
// moved, switched LoD level or, emitting, changed the light they cast since the previous frame;
// an instance that stayed put is untouched, whatever else moved (and the camera's motion is not a
// change of any instance). An emitter is added as a third instance.
TEST_F(SceneHistory, InstanceRecordsSayWhatChanged) {
  scene::Scene s = two_quads();
  scene::Material light;
  light.emission = glm::vec3(4.0f);
  s.materials.push_back(light);
  scene::Mesh lamp = unit_quad();
  lamp.primitives[0].material = 1;
  s.meshes.push_back(lamp);
  s.instances.push_back({"lamp", {2}, glm::translate(glm::mat4(1.0f), glm::vec3(0, 3, 0)), 0});
  render::GpuScene gs(gpu_context(), s, /*keep_history=*/true);
  auto update = [&](scene::FrameState f) {
    gpu_context().submit_and_wait([&](VkCommandBuffer cmd) { gs.record_update(cmd, f); });
    auto records = gs.instances().download_as<gpu::GpuInstance>(3);
    std::vector<uint32_t> device;
    for (const auto& r : records) device.push_back(r.flags & gpu::INSTANCE_CHANGED);
    EXPECT_EQ(device, gs.instance_changes()) << "host and device disagree";
    return device;
  };
  scene::FrameState f0 = state(s, 0);
  f0.transforms.push_back(s.instances[2].transform);
  f0.lods.push_back(0);
  EXPECT_EQ(update(f0), (std::vector<uint32_t>{0, 0, 0})) << "the first frame has nothing to compare with";
  scene::FrameState f1 = state(s, 1);  // the mover moves and switches level; the camera moves too
  f1.transforms.push_back(s.instances[2].transform);
  f1.lods.push_back(0);
  EXPECT_EQ(update(f1), (std::vector<uint32_t>{gpu::INSTANCE_CHANGED_TRANSFORM | gpu::INSTANCE_CHANGED_LOD, 0, 0}));
  EXPECT_EQ(gs.changed_instances(), 1u);
  scene::FrameState f2 = f1;  // only the lamp moves
  f2.transforms[2] = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 3, 0));
  EXPECT_EQ(update(f2), (std::vector<uint32_t>{0, 0, gpu::INSTANCE_CHANGED_TRANSFORM | gpu::INSTANCE_CHANGED_EMISSION}));
  EXPECT_TRUE(gs.moved_since_previous());
  EXPECT_EQ(update(f2), (std::vector<uint32_t>{0, 0, 0})) << "the same state again";
  EXPECT_FALSE(gs.moved_since_previous());
}

TEST_F(SceneHistory, WithoutHistoryThereIsOneSlotAndNoExtraMemory) {
  scene::Scene s = two_quads();
  render::GpuScene plain(gpu_context(), s), kept(gpu_context(), s, /*keep_history=*/true);
  EXPECT_FALSE(plain.keeps_history());
  auto a = plain.memory(), b = kept.memory();
  EXPECT_EQ(a.history, 0u);
  EXPECT_EQ(a.geometry, b.geometry);
  EXPECT_EQ(a.acceleration, b.acceleration);
  EXPECT_EQ(a.per_frame, b.per_frame);
  // The history costs exactly one more TLAS with its scratch, one more instance buffer and the
  // changed instances' swept boxes (suffix auto).
  EXPECT_EQ(b.history,
            plain.tlas().bytes() + plain.tlas().scratch_bytes() + plain.instances().size() + sizeof(gpu::GpuSweptBoxes));
  for (int k = 0; k < 3; ++k) {
    scene::FrameState f = state(s, k % 2);
    gpu_context().submit_and_wait([&](VkCommandBuffer cmd) { plain.record_update(cmd, f); });
    EXPECT_EQ(plain.parity(), 0);
    EXPECT_FALSE(plain.history_valid());
    EXPECT_EQ(plain.moved_since_previous(), k > 0);
  }
  EXPECT_EQ(plain.tlas_builds(), 3u) << "the LoD level switches every frame";
  EXPECT_THROW(render::RayProbe(gpu_context(), s).trace(state(s, 0), k_rays, render::ProbeSlot::previous), std::logic_error);

  render::RenderSettings rs;
  rs.width = rs.height = 4;
  render::Renderer pt(gpu_context(), s, rs);
  EXPECT_FALSE(pt.gpu_scene().keeps_history());
  EXPECT_EQ(pt.memory_bytes().count("scene_history"), 0u);
}

}  // namespace
}  // namespace strata::test
