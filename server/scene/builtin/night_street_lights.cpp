// night-street's lights (night_street.h): 64 KHR_lights_punctual lights in five groups, in this
// order:
//   16 street lamps: warm spots 5.8 m up on posts at the curbs, every 8 m along each side, aimed
//      down at the road (cones 30 and 55 degrees, 45-110 cd);
//   12 shop-front lights: points under each building's sign, of varied colour (3-9 cd);
//   12 lanterns: paper lanterns on brackets 4.3 m up the facades, swinging along the street (each
//      its own period and phase; the light and its frame follow one pendulum);
//    8 car lights: two cars, one driving away in the right lane at 10 m/s and one coming towards
//      the camera in the left lane at 11 m/s, each with two headlight spots and two red tail
//      lights that follow the car;
//   16 far lights: floodlights in the cross street at the far end aimed at a billboard, and
//      high-mast sodium spots 12 m up along the cross street, 55-70 m from the camera. They carry
//      most of the scene's power (about 70% of the punctual lights', 60% of the light table's with
//      the windows) but light little of what the camera sees: a light picked in proportion to its
//      power is mostly one of them.
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/builtin/night_street.h"
#include "scene/builtin/random.h"
#include "scene/builtin/shapes.h"

namespace strata::scene::builtin::night_street {
namespace {

glm::mat4 at(const glm::vec3& p) { return glm::translate(glm::mat4(1.0f), p); }

Light spot(const std::string& name, glm::vec3 color, float intensity, glm::vec3 position, glm::vec3 direction,
           float inner_degrees, float outer_degrees) {
  Light l = light_at(name, LightType::kSpot, color, intensity, position, direction);
  l.inner_cone = glm::radians(inner_degrees);
  l.outer_cone = glm::radians(outer_degrees);
  return l;
}

// Lamp posts at the curbs: a pole, an arm over the road and a head above the light.
void add_street_lamps(SceneBuilder& b, uint32_t metal, Pcg32& rng) {
  Primitive posts;
  posts.material = metal;
  for (uint32_t k = 0; k < 16; ++k) {
    const float side = k < 8 ? -1.0f : 1.0f;  // left side first
    const float z = kNearZ - 8.0f * float(k % 8) - (side > 0.0f ? 4.0f : 0.0f);
    const float pole_x = side * (kRoadHalfWidth + 0.4f), light_x = side * (kRoadHalfWidth - 0.7f);
    append(posts, transformed(cylinder(0.08f, 6.0f, 6, metal), at({pole_x, kCurb, z})));
    append(posts, transformed(box({0.55f, 0.04f, 0.04f}, metal), at({0.5f * (pole_x + light_x), 6.0f, z})));
    append(posts, transformed(box({0.25f, 0.06f, 0.15f}, metal), at({light_x, 5.9f, z})));
    // Sodium orange or warm white, of varied age (intensity).
    const glm::vec3 color = rng.uniform() < 0.5f ? glm::vec3(1.0f, 0.6f, 0.28f) : glm::vec3(1.0f, 0.82f, 0.6f);
    b.light(spot("street lamp " + std::to_string(k), color, rng.uniform(45.0f, 110.0f), {light_x, 5.78f, z},
                 {-side * 0.25f, -1.0f, 0.0f}, 30.0f, 55.0f));
  }
  b.instance("lamp posts", b.mesh("lamp posts", {posts}));
}

// One point light under each building's sign, 0.8 m out from the facade.
void add_shop_lights(SceneBuilder& b, Pcg32& rng) {
  const glm::vec3 colors[4] = {{1.0f, 0.85f, 0.65f}, {1.0f, 0.45f, 0.6f}, {0.45f, 0.85f, 1.0f}, {1.0f, 0.7f, 0.3f}};
  for (uint32_t k = 0; k < 2 * kBlocks; ++k) {
    const float side = k < kBlocks ? -1.0f : 1.0f;
    const float z = kNearZ - kBlockLength * (float(k % kBlocks) + 0.5f);
    b.light(light_at("shop light " + std::to_string(k), LightType::kPoint, colors[rng.next() % 4],
                     rng.uniform(3.0f, 9.0f), {side * (kFacadeX - 0.8f), 2.8f, z}, {0, 0, -1}));
  }
}

// Lanterns: a bracket on the facade holds a pivot 0.6 m out; the lantern (rod, cap, the light,
// a base) hangs 0.55 m below it and swings about the street's cross axis.
void add_lanterns(SceneBuilder& b, uint32_t metal, uint32_t frame, Pcg32& rng) {
  Primitive lantern = transformed(box({0.01f, 0.2f, 0.01f}, frame), at({0.0f, -0.2f, 0.0f}));
  append(lantern, transformed(box({0.12f, 0.03f, 0.12f}, frame), at({0.0f, -0.43f, 0.0f})));
  append(lantern, transformed(box({0.1f, 0.02f, 0.1f}, frame), at({0.0f, -0.68f, 0.0f})));
  const uint32_t mesh = b.mesh("lantern", {lantern});
  Primitive brackets;
  brackets.material = metal;
  const glm::vec3 colors[3] = {{1.0f, 0.45f, 0.2f}, {1.0f, 0.3f, 0.15f}, {1.0f, 0.7f, 0.4f}};
  for (uint32_t k = 0; k < 12; ++k) {
    const float side = k < 6 ? -1.0f : 1.0f;
    const glm::vec3 pivot(side * (kFacadeX - 0.6f), 4.3f, kNearZ - 1.5f - kBlockLength * float(k % 6));
    append(brackets, transformed(box({0.3f, 0.02f, 0.02f}, metal), at(pivot + glm::vec3(side * 0.3f, 0.0f, 0.0f))));
    const float period = rng.uniform(36.0f, 54.0f), phase = rng.uniform(0.0f, 2.0f * kPi);
    const float amplitude = rng.uniform(0.15f, 0.3f);
    auto swing = [=](uint32_t f) {
      return glm::angleAxis(amplitude * std::sin(2.0f * kPi * float(f) / period + phase), glm::vec3(1, 0, 0));
    };
    const std::string name = "lantern " + std::to_string(k);
    const uint32_t instance = b.instance(name, mesh);
    b.track(instance, [&](uint32_t f) {
      TransformKey key;
      key.translation = pivot;
      key.rotation = swing(f);
      return key;
    });
    const uint32_t light = b.light(light_at(name, LightType::kPoint, colors[rng.next() % 3], rng.uniform(1.5f, 3.0f),
                                            glm::vec3(0.0f), {0, 0, -1}));
    b.light_track(light, [&](uint32_t f) {
      TransformKey key;
      key.translation = pivot + swing(f) * glm::vec3(0.0f, -0.55f, 0.0f);
      return key;
    });
  }
  b.instance("lantern brackets", b.mesh("lantern brackets", {brackets}));
}

// A car: body, cabin (glass) and four wheels, its front towards -Z.
uint32_t car_mesh(SceneBuilder& b, const std::string& name, uint32_t paint, const FixtureMaterials& m) {
  Primitive body = transformed(box({0.9f, 0.35f, 2.1f}, paint), at({0.0f, 0.6f, 0.0f}));
  Primitive cabin = transformed(box({0.8f, 0.28f, 1.1f}, m.glass), at({0.0f, 1.23f, 0.2f}));
  Primitive wheels;
  wheels.material = m.tyre;
  for (const float x : {-0.85f, 0.85f})
    for (const float z : {-1.35f, 1.35f}) append(wheels, transformed(box({0.12f, 0.3f, 0.3f}, m.tyre), at({x, 0.3f, z})));
  return b.mesh(name, {body, cabin, wheels});
}

// A car moving along z at `speed` (m/s, negative: away from the camera) in the lane at `x`, and its
// four lights placed on it every frame: headlights (spots, cones 10 and 22 degrees) and tail lights
// (spots shining backwards over a half-space, 6 cm behind the body, which they leave unlit: a point
// light there would make a bright spot on the paint, a source of fireflies for every path that
// bounces off it).
void add_car(SceneBuilder& b, const std::string& name, uint32_t mesh, float x, float z0, float speed) {
  const glm::quat heading = speed < 0.0f ? glm::quat(1, 0, 0, 0) : glm::angleAxis(kPi, glm::vec3(0, 1, 0));
  auto place = [=](uint32_t f) {
    TransformKey key;
    key.translation = {x, 0.0f, z0 + speed * key_time(f)};
    key.rotation = heading;
    return key;
  };
  b.track(b.instance(name, mesh), place);
  struct Lamp {
    const char* name;
    glm::vec3 offset;  // in the car's frame
    bool head;
  };
  const Lamp lamps[4] = {{"headlight left", {-0.6f, 0.65f, -2.15f}, true},
                         {"headlight right", {0.6f, 0.65f, -2.15f}, true},
                         {"tail light left", {-0.65f, 0.75f, 2.16f}, false},
                         {"tail light right", {0.65f, 0.75f, 2.16f}, false}};
  for (const Lamp& lamp : lamps) {
    const std::string light_name = name + " " + lamp.name;
    const uint32_t light =
        lamp.head ? b.light(spot(light_name, {1.0f, 0.95f, 0.85f}, 120.0f, glm::vec3(0.0f), {0, 0, -1}, 10.0f, 22.0f))
                  : b.light(spot(light_name, {1.0f, 0.05f, 0.02f}, 0.8f, glm::vec3(0.0f), {0, 0, -1}, 60.0f, 85.0f));
    const glm::quat aim = look_at(glm::vec3(0.0f), lamp.head ? glm::vec3(0.0f, -0.12f, -1.0f) : glm::vec3(0.0f, 0.0f, 1.0f));
    b.light_track(light, [&](uint32_t f) {
      TransformKey key = place(f);
      key.translation += key.rotation * lamp.offset;
      key.rotation = key.rotation * aim;
      return key;
    });
  }
}

// Floodlights on the cross street's far kerb aimed up at the billboard, and high masts along it
// shining down on it.
void add_far_lights(SceneBuilder& b) {
  const glm::vec3 billboard(0.0f, 10.5f, kFarFacadeZ);
  for (uint32_t k = 0; k < 8; ++k) {
    const glm::vec3 p(-10.5f + 3.0f * float(k), 0.6f, kFarFacadeZ + 6.5f);
    b.light(spot("floodlight " + std::to_string(k), {0.85f, 0.9f, 1.0f}, 500.0f, p, billboard - p, 8.0f, 16.0f));
  }
  for (uint32_t k = 0; k < 8; ++k) {
    const float x = (k % 2 == 0 ? -1.0f : 1.0f) * (6.0f + 5.0f * float(k / 2));
    b.light(spot("high mast " + std::to_string(k), {1.0f, 0.7f, 0.4f}, 400.0f, {x, 12.0f, kFarFacadeZ + 4.0f},
                 {0.0f, -1.0f, 0.0f}, 40.0f, 65.0f));
  }
}

}  // namespace

void add_lights(SceneBuilder& b, const FixtureMaterials& m) {
  Pcg32 rng(0x11647u);
  add_street_lamps(b, m.metal, rng);
  add_shop_lights(b, rng);
  add_lanterns(b, m.metal, m.frame, rng);
  add_car(b, "car away", car_mesh(b, "car red", m.paint[0], m), 2.0f, 4.0f, -10.0f);
  add_car(b, "car towards", car_mesh(b, "car blue", m.paint[1], m), -2.0f, -50.0f, 11.0f);
  add_far_lights(b);
}

}  // namespace strata::scene::builtin::night_street
