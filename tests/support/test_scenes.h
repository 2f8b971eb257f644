#pragma once
// Small analytic scenes built in code for tests.
#include <string>

#include "scene/scene.h"

namespace strata::test {

// A closed axis-aligned box [-h, h]^3 seen from inside: 6 quads facing inward, Lambert albedo
// `albedo` (no specular lobe), each emitting `emission` from its inward face. The camera sits at the
// centre looking down -Z. Radiance everywhere is emission / (1 - albedo) (white furnace).
scene::Scene furnace_box(float albedo, float emission, float half_size = 1.0f);

// The index of the instance called `name` (throws std::runtime_error when there is none).
uint32_t instance_named(const scene::Scene& s, const std::string& name);

// cornell's frame state with its short box flattened into a slab 20 cm under the ceiling light
// (a 2 cm gap to the ceiling): the last segment of nearly every path to the light is blocked,
// while what the camera sees and the first bounces stay in place (suffix auto's tests).
scene::FrameState cornell_light_shaded(const scene::Scene& cornell);

// A method name as a gtest parameter name ("restir-gather" -> "restir_gather").
std::string method_test_name(const std::string& method);
// Frame `scene_frame` of the scene's animation with every LoD group at level f % 2 (a switch at
// every frame: the LoD-aware reuse tests).
scene::FrameState lod_switched(const scene::Scene& s, uint32_t scene_frame, uint32_t f);

// One quad of size 2h x 2h in the plane z = z0, facing +Z, with one material.
scene::Mesh quad_mesh(float half, float z0, uint32_t material);

// A white Lambert plane (albedo 1: base colour 1, no specular lobe), 20 m across at z = 0 facing +Z,
// seen by a camera at (0, 0, 3) looking down -Z through a 0.004 rad field of view (the pixels see
// points within 6 mm of the origin). Nothing lights it: tests add the light they check.
scene::Scene white_plane(const std::string& name);

// Two planes facing a camera at (0, 0, 4) that looks down -Z: the back plane (instance "back",
// z = 0, 2 m half size, grey Lambert) and the front quad (instance "front", z = 1, half size
// `front_half`, orange Lambert), lit by a one-sided emitter between them off to the side
// (instance "light", z = 0.5, x in [1.4, 6], facing -Z, outside the view) and by a constant
// environment `environment`. With environment 0 no ray from the back plane to the light reaches
// z = 1, and the light sends nothing upwards, so for paths of up to two segments after the camera
// (max_depth <= 2) the back plane's radiance does not depend on the front quad: ML Eq. 3's I_2
// of the back plane equals what the camera sees with the front quad removed (front_half = 0: none).
scene::Scene two_planes(float front_half, float environment = 0.0f);

}  // namespace strata::test
