// chess: a 4 m x 4 m board (8 x 8 squares in two materials, on a frame) with three high-poly
// pieces turned on a lathe: a pawn, a queen and a rook with six crenellations. Each piece has
// three LoD levels from make_lod_chain (about 1, 1/4, 1/16 of its triangles); UVs are
// u = angle / 2pi, v = profile parameter, with the seam vertices duplicated (the rook's body in
// v < 0.75, its merlons' faces in cells above: no two points share a UV).
// Light: a 1.5 m x 1.5 m area light 4 m above the board (radiance 12) and a dim environment.
// Animation: the pawn slides two squares, the queen slides diagonally while turning 45 degrees,
// the rook slides and spins; the camera orbits 40 degrees. LoD schedule: the rook changes level
// every 10 frames (0, 1, 2, 1, 0, ...), the queen goes 2 -> 1 -> 0, the pawn 0 -> 1.
#include <cmath>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/builtin/builtins.h"
#include "scene/builtin/common.h"
#include "scene/builtin/shapes.h"
#include "scene/lod.h"

namespace strata::scene::builtin {
namespace {

constexpr uint32_t kSegments = 112;

// Uniform Catmull-Rom through `control`, `samples` points per span (end points included once).
std::vector<ProfilePoint> smooth(const std::vector<glm::vec2>& c, uint32_t samples) {
  std::vector<ProfilePoint> out;
  for (size_t i = 0; i + 1 < c.size(); ++i) {
    const glm::vec2 p0 = c[i > 0 ? i - 1 : i], p1 = c[i], p2 = c[i + 1],
                    p3 = c[i + 2 < c.size() ? i + 2 : i + 1];
    for (uint32_t s = 0; s < samples; ++s) {
      const float t = static_cast<float>(s) / static_cast<float>(samples);
      const float t2 = t * t, t3 = t2 * t;
      out.push_back(0.5f *
                    (2.0f * p1 + (p2 - p0) * t + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * t2 +
                     (3.0f * p1 - p0 - 3.0f * p2 + p3) * t3));
    }
  }
  out.push_back(c.back());
  return out;
}

// Joins profile pieces; the shared point is repeated, which makes a hard edge there.
std::vector<ProfilePoint> join(std::initializer_list<std::vector<ProfilePoint>> pieces) {
  std::vector<ProfilePoint> out;
  for (const auto& piece : pieces) out.insert(out.end(), piece.begin(), piece.end());
  return out;
}

std::vector<ProfilePoint> line(glm::vec2 a, glm::vec2 b, uint32_t steps) {
  std::vector<ProfilePoint> out;
  for (uint32_t s = 0; s <= steps; ++s)
    out.push_back(glm::mix(a, b, static_cast<float>(s) / static_cast<float>(steps)));
  return out;
}

Primitive pawn(uint32_t material) {
  return lathe(join({line({0, 0}, {0.18f, 0}, 4), smooth({{0.18f, 0},
                                                          {0.18f, 0.03f},
                                                          {0.16f, 0.055f},
                                                          {0.13f, 0.065f},
                                                          {0.1f, 0.08f},
                                                          {0.08f, 0.12f},
                                                          {0.068f, 0.18f},
                                                          {0.065f, 0.22f},
                                                          {0.07f, 0.245f},
                                                          {0.1f, 0.255f},
                                                          {0.105f, 0.265f},
                                                          {0.095f, 0.275f},
                                                          {0.06f, 0.285f},
                                                          {0.05f, 0.29f},
                                                          {0.07f, 0.31f},
                                                          {0.078f, 0.35f},
                                                          {0.07f, 0.385f},
                                                          {0.045f, 0.413f},
                                                          {0, 0.425f}},
                                                         3)}),
               kSegments, material);
}

Primitive queen(uint32_t material) {
  return lathe(join({line({0, 0}, {0.2f, 0}, 4),
                     smooth({{0.2f, 0},
                             {0.2f, 0.035f},
                             {0.17f, 0.06f},
                             {0.14f, 0.075f},
                             {0.11f, 0.1f},
                             {0.09f, 0.16f},
                             {0.075f, 0.3f},
                             {0.07f, 0.42f},
                             {0.09f, 0.45f},
                             {0.11f, 0.46f},
                             {0.09f, 0.475f},
                             {0.075f, 0.5f},
                             {0.085f, 0.58f},
                             {0.11f, 0.64f},
                             {0.12f, 0.66f}},
                            3),
                     smooth({{0.12f, 0.66f},
                             {0.09f, 0.67f},
                             {0.07f, 0.68f},
                             {0.05f, 0.7f},
                             {0.03f, 0.72f},
                             {0.035f, 0.735f},
                             {0.03f, 0.75f},
                             {0, 0.76f}},
                            3)}),
               kSegments, material);
}

Primitive rook(uint32_t material) {
  Primitive body =
      lathe(join({line({0, 0}, {0.19f, 0}, 4),
                  smooth({{0.19f, 0},
                          {0.19f, 0.03f},
                          {0.16f, 0.05f},
                          {0.13f, 0.07f},
                          {0.115f, 0.1f},
                          {0.11f, 0.17f},
                          {0.11f, 0.25f},
                          {0.115f, 0.3f},
                          {0.14f, 0.32f},
                          {0.15f, 0.33f},
                          {0.15f, 0.4f}},
                         5),
                  line({0.15f, 0.4f}, {0.1f, 0.4f}, 2), line({0.1f, 0.4f}, {0.1f, 0.37f}, 2),
                  line({0.1f, 0.37f}, {0, 0.37f}, 3)}),
            kSegments, material);
  // Six merlons standing on the rim. Every point keeps a UV of its own (tau, LOD 4.2, finds a point's
  // images through its UV): the body's chart takes v in [0, 0.75], and the merlons' 36 faces, which
  // box() lays out on one shared unit square, get cells of a 12 x 3 strip above it.
  for (glm::vec2& uv : body.uvs) uv.y *= 0.75f;
  for (int k = 0; k < 6; ++k) {
    const float angle = 2.0f * kPi * static_cast<float>(k) / 6.0f;
    glm::mat4 m = glm::rotate(glm::mat4(1.0f), angle, glm::vec3(0, 1, 0));
    m = glm::translate(m, {0.125f, 0.43f, 0.0f});
    Primitive merlon = transformed(box({0.025f, 0.03f, 0.035f}, material, 4), m);
    const size_t per_face = merlon.uvs.size() / 6;
    for (size_t i = 0; i < merlon.uvs.size(); ++i) {
      const size_t cell = static_cast<size_t>(k) * 6 + i / per_face;
      const glm::vec2 origin(static_cast<float>(cell % 12) / 12.0f, 0.77f + 0.08f * static_cast<float>(cell / 12));
      merlon.uvs[i] = origin + merlon.uvs[i] * glm::vec2(1.0f / 12.0f - 0.01f, 0.07f);
    }
    append(body, merlon);
  }
  return body;
}

glm::vec3 square(float file, float rank) {
  return {-1.75f + 0.5f * file, 0.0f, 1.75f - 0.5f * rank};
}

float ease(uint32_t frame, uint32_t begin, uint32_t end) {
  const float t = glm::clamp(
      (static_cast<float>(frame) - static_cast<float>(begin)) / static_cast<float>(end - begin),
      0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

uint32_t add_piece(SceneBuilder& b, const std::string& name, const Primitive& piece, uint32_t lod) {
  std::vector<uint32_t> levels;
  const std::vector<Primitive> chain = make_lod_chain(piece, 3, 0.25f);
  for (size_t l = 0; l < chain.size(); ++l)
    levels.push_back(b.mesh(name + "_lod" + std::to_string(l), {chain[l]}));
  return b.instance(name, levels, glm::mat4(1.0f),
                    std::min<uint32_t>(lod, static_cast<uint32_t>(levels.size() - 1)));
}

}  // namespace

Scene make_chess() {
  SceneBuilder b("chess");
  const uint32_t light_square = b.material("light_square", {0.8f, 0.75f, 0.65f}, 0.0f, 0.5f);
  const uint32_t dark_square = b.material("dark_square", {0.25f, 0.15f, 0.1f}, 0.0f, 0.5f);
  const uint32_t frame = b.material("frame", {0.3f, 0.2f, 0.12f}, 0.0f, 0.6f);
  const uint32_t ivory = b.material("ivory", {0.85f, 0.82f, 0.75f}, 0.0f, 0.25f);
  const uint32_t ebony = b.material("ebony", {0.12f, 0.1f, 0.09f}, 0.0f, 0.35f);
  const uint32_t light = b.emitter("light", {12.0f, 12.0f, 11.0f});

  Primitive light_squares, dark_squares;
  light_squares.material = light_square;
  dark_squares.material = dark_square;
  for (int rank = 0; rank < 8; ++rank) {
    for (int file = 0; file < 8; ++file) {
      const glm::vec3 corner =
          square(static_cast<float>(file), static_cast<float>(rank)) + glm::vec3(-0.25f, 0, 0.25f);
      const bool dark = (rank + file) % 2 == 0;
      append(dark ? dark_squares : light_squares,
             quad(corner, {0.5f, 0, 0}, {0, 0, -0.5f}, dark ? dark_square : light_square));
    }
  }
  b.instance("board", b.mesh("board", {std::move(light_squares), std::move(dark_squares)}));
  b.instance("frame", b.mesh("frame", {box({2.2f, 0.1f, 2.2f}, frame)}),
             glm::translate(glm::mat4(1.0f), {0.0f, -0.105f, 0.0f}));

  const uint32_t pawn_id = add_piece(b, "pawn", pawn(ivory), 0);
  const uint32_t queen_id = add_piece(b, "queen", queen(ebony), 2);
  const uint32_t rook_id = add_piece(b, "rook", rook(ivory), 0);
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  b.track(pawn_id, [&](uint32_t f) {
    TransformKey key;
    key.translation = glm::mix(square(4, 1), square(4, 3), ease(f, 0, 60));
    return key;
  });
  b.track(queen_id, [&](uint32_t f) {
    TransformKey key;
    key.translation = glm::mix(square(3, 7), square(6, 4), ease(f, 30, 110));
    key.rotation = glm::angleAxis(0.25f * kPi * ease(f, 30, 110), up);
    return key;
  });
  b.track(rook_id, [&](uint32_t f) {
    TransformKey key;
    key.translation = glm::mix(square(0, 0), square(0, 2), ease(f, 0, kFrameCount - 1));
    key.rotation = glm::angleAxis(0.5f * kPi * ease(f, 0, kFrameCount - 1), up);
    return key;
  });
  const uint32_t rook_levels =
      static_cast<uint32_t>(b.scene().instances[rook_id].lod_meshes.size());
  const uint32_t queen_levels =
      static_cast<uint32_t>(b.scene().instances[queen_id].lod_meshes.size());
  const uint32_t rook_cycle[4] = {0, 1, 2, 1};
  for (uint32_t f = 0; f < kFrameCount; f += 10)
    b.lod_key(f, rook_id, std::min(rook_cycle[(f / 10) % 4], rook_levels - 1));
  b.lod_key(0, queen_id, queen_levels - 1);
  b.lod_key(40, queen_id, queen_levels > 1 ? queen_levels - 2 : 0);
  b.lod_key(80, queen_id, 0);
  b.lod_key(0, pawn_id, 0);
  b.lod_key(60, pawn_id, 1);

  b.instance("light", b.mesh("light", {facing_quad({0.0f, 4.0f, 0.0f}, -up, 1.5f, 1.5f, light)}));
  b.scene().environment.radiance = glm::vec3(0.02f);

  const glm::vec3 target(0.0f, 0.2f, 0.0f);
  auto orbit = [&](uint32_t f) {
    const float angle =
        glm::radians(-20.0f + 40.0f * static_cast<float>(f) / static_cast<float>(kFrameCount - 1));
    return std::pair{glm::vec3(5.0f * std::sin(angle), 3.0f, 5.0f * std::cos(angle)), target};
  };
  b.camera(orbit(0).first, target, 0.75f);
  b.camera_path(orbit);
  return b.finish();
}

}  // namespace strata::scene::builtin
