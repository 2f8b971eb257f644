// The emitter density that MIS weights use (sampling/emitter_pdf.h, in pt and every ReSTIR pass)
// is the density the host's alias table samples with (render/emitters.cpp): for every emitter
// triangle of a built-in scene, (1 - env_select) pmf / area * d^2 / |cos| from the table equals
// emitter_solid_angle_pdf computed from the material, to float rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "render/emitters.h"
#include "sampling/emitter_pdf.h"
#include "scene/scene_io.h"

namespace strata::test {
namespace {

TEST(EmitterPdf, MatchesTheAliasTablesSelectionForEveryEmitter) {
  for (const char* name : {"cornell", "stiff", "carousel"}) {
    scene::Scene s = scene::builtin_scene(name);
    scene::FrameState f = s.frame_state(0);
    render::EmitterTable t = render::build_emitter_table(s, f, glm::dvec3(f.camera.position));
    ASSERT_FALSE(t.emitters.empty()) << name;
    const float env_select = 0.25f, distance = 3.0f, cos_light = 0.6f;
    for (const auto& e : t.emitters) {
      const float area = e.p0_area.w;
      uint32_t flags;
      std::memcpy(&flags, &e.p2_flags.w, sizeof flags);
      const bool double_sided = (flags & gpu::MATERIAL_DOUBLE_SIDED) != 0u;
      const double table = (1.0 - env_select) * double(e.p1_pmf.w) / area * distance * distance / cos_light;
      const float pdf = gpu::emitter_solid_angle_pdf(float(t.total_power), env_select, glm::vec3(e.emission), area, double_sided,
                                                     distance, -cos_light);  // |cos|: either side
      EXPECT_NEAR(pdf / table, 1.0, 1e-5) << name;
    }
  }
  EXPECT_EQ(gpu::emitter_solid_angle_pdf(0.0f, 0.0f, glm::vec3(1.0f), 1.0f, false, 1.0f, 1.0f), 0.0f);  // no emitters
  EXPECT_EQ(gpu::emitter_solid_angle_pdf(1.0f, 0.0f, glm::vec3(1.0f), 0.0f, false, 1.0f, 1.0f), 0.0f);  // degenerate
  EXPECT_EQ(gpu::emitter_solid_angle_pdf(1.0f, 0.0f, glm::vec3(1.0f), 1.0f, false, 1.0f, 0.0f), 0.0f);  // edge-on
}

}  // namespace
}  // namespace strata::test
