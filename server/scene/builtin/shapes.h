#pragma once
// Procedural primitives for the built-in scenes. All wind counter-clockwise seen from outside
// (the side the normals point to) and carry UVs; curved shapes duplicate their seam vertices so
// the UVs stay continuous.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace strata::scene::builtin {

// A parallelogram origin, origin+u, origin+u+v, origin+v facing along cross(u, v), split into
// cells x cells quads; uv spans [0,1]^2.
Primitive quad(const glm::vec3& origin, const glm::vec3& u, const glm::vec3& v, uint32_t material,
               uint32_t cells = 1);
// A rectangle of size w x h centred at `center` facing `normal`.
Primitive facing_quad(const glm::vec3& center, const glm::vec3& normal, float width, float height,
                      uint32_t material);
// Axis-aligned box centred at the origin; each face maps to the full [0,1]^2 UV square and is
// split into cells x cells quads.
Primitive box(const glm::vec3& half_extent, uint32_t material, uint32_t cells = 1);

// A point of a lathe profile: radius and height. A repeated point makes a hard edge.
using ProfilePoint = glm::vec2;
// Surface of revolution about +Y: u = angle / 2pi, v = index along the profile / (n - 1).
Primitive lathe(const std::vector<ProfilePoint>& profile, uint32_t segments, uint32_t material);
Primitive uv_sphere(float radius, uint32_t segments, uint32_t rings, uint32_t material);
Primitive cylinder(float radius, float height, uint32_t segments,
                   uint32_t material);  // base at y = 0

// Height field over [-size/2, size/2]^2 in x/z with n x n vertices; uv = grid coords / (n - 1).
template <typename Height>
Primitive height_field(float size, uint32_t n, uint32_t material, Height height);

// The Cornell box's five walls, 2 m: x in [-1, 1], y in [0, 2], z in [-1, 1], open towards +z;
// floor, ceiling and back wall of `white`, the left wall `red`, the right wall `green`, each facing
// into the box.
std::vector<Primitive> cornell_walls(uint32_t white, uint32_t red, uint32_t green);

// `count` leaf cards (size x size squares, for a double-sided MASK material) around the +Y axis
// `radius` out, `per_ring` to a ring, rings from height y0 up by `step`, each card leaning at
// random (seeded, so a crown builds the same way every time).
Primitive leaf_cards(uint32_t count, uint32_t per_ring, float y0, float step, float size, float radius,
                     uint32_t material, uint64_t seed);

// A rectangular opening in a wall: [s0, s1] along the wall's width, [t0, t1] up its height (metres).
struct Opening {
  float s0, s1, t0, t1;
};
// A wall origin + s u_dir + t v_dir (s in [0, width], t in [0, height]) facing along
// cross(u_dir, v_dir), with rectangular holes and, around each hole, a reveal `depth` deep behind
// the wall (four quads facing into the hole). UVs are metres (s, t) on the wall, [0, 1]^2 on each reveal.
Primitive wall_with_openings(const glm::vec3& origin, const glm::vec3& u_dir, const glm::vec3& v_dir, float width,
                             float height, const std::vector<Opening>& openings, float depth, uint32_t material);

// UVs in metres projected onto the plane of `u_dir` and `v_dir` (unit vectors): uv = (p.u_dir, p.v_dir).
Primitive with_planar_uvs(Primitive p, const glm::vec3& u_dir, const glm::vec3& v_dir);

// Applies `m` to positions and normals (normals by the inverse transpose).
Primitive transformed(Primitive p, const glm::mat4& m);
// Appends `b` to `a` (same material assumed: a's is kept).
void append(Primitive& a, const Primitive& b);

// Implementation of height_field: vertices, then triangles, then normals from the triangles.
Primitive grid_from_heights(float size, uint32_t n, uint32_t material,
                            const std::vector<float>& heights);

template <typename Height>
Primitive height_field(float size, uint32_t n, uint32_t material, Height height) {
  std::vector<float> heights;
  heights.reserve(static_cast<size_t>(n) * n);
  for (uint32_t j = 0; j < n; ++j) {
    for (uint32_t i = 0; i < n; ++i) {
      const float x = (static_cast<float>(i) / static_cast<float>(n - 1) - 0.5f) * size;
      const float z = (static_cast<float>(j) / static_cast<float>(n - 1) - 0.5f) * size;
      heights.push_back(height(x, z));
    }
  }
  return grid_from_heights(size, n, material, heights);
}

}  // namespace strata::scene::builtin
