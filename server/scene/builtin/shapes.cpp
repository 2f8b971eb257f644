#include "scene/builtin/shapes.h"

#include <algorithm>
#include <cmath>

#include "scene/builtin/random.h"
#include "scene/normals.h"

namespace strata::scene::builtin {
namespace {

void push_vertex(Primitive& p, const glm::vec3& position, const glm::vec3& normal,
                 const glm::vec2& uv) {
  p.positions.push_back(position);
  p.normals.push_back(normal);
  p.uvs.push_back(uv);
}

void push_triangle(Primitive& p, uint32_t a, uint32_t b, uint32_t c) {
  p.indices.insert(p.indices.end(), {a, b, c});
}

float fraction(uint32_t i, uint32_t n) {
  return static_cast<float>(i) / static_cast<float>(n);
}

// Profile tangent at point i; a repeated point takes the tangent of the segment on its other
// side, which is what turns a repeated point into a hard edge.
glm::vec2 profile_tangent(const std::vector<ProfilePoint>& profile, size_t i) {
  const size_t last = profile.size() - 1;
  const bool same_as_next = i < last && profile[i + 1] == profile[i];
  const bool same_as_prev = i > 0 && profile[i - 1] == profile[i];
  if (i == 0 || same_as_prev) return profile[i + 1] - profile[i];
  if (i == last || same_as_next) return profile[i] - profile[i - 1];
  return profile[i + 1] - profile[i - 1];
}

}  // namespace

Primitive quad(const glm::vec3& origin, const glm::vec3& u, const glm::vec3& v, uint32_t material,
               uint32_t cells) {
  Primitive p;
  p.material = material;
  const glm::vec3 normal = glm::normalize(glm::cross(u, v));
  for (uint32_t j = 0; j <= cells; ++j) {
    for (uint32_t i = 0; i <= cells; ++i) {
      const glm::vec2 uv(fraction(i, cells), fraction(j, cells));
      push_vertex(p, origin + u * uv.x + v * uv.y, normal, uv);
    }
  }
  for (uint32_t j = 0; j < cells; ++j) {
    for (uint32_t i = 0; i < cells; ++i) {
      const uint32_t a = j * (cells + 1) + i;
      const uint32_t d = a + cells + 1;
      push_triangle(p, a, a + 1, d + 1);
      push_triangle(p, a, d + 1, d);
    }
  }
  return p;
}

Primitive facing_quad(const glm::vec3& center, const glm::vec3& normal, float width, float height,
                      uint32_t material) {
  const glm::vec3 n = glm::normalize(normal);
  const glm::vec3 helper =
      std::abs(n.y) < 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(0.0f, 0.0f, 1.0f);
  const glm::vec3 t = glm::normalize(glm::cross(helper, n));
  const glm::vec3 b = glm::cross(n, t);  // cross(t, b) = n
  const glm::vec3 u = t * width;
  const glm::vec3 v = b * height;
  return quad(center - 0.5f * u - 0.5f * v, u, v, material);
}

Primitive box(const glm::vec3& h, uint32_t material, uint32_t cells) {
  // (origin, u, v) per face with cross(u, v) pointing out of the box.
  const glm::vec3 faces[6][3] = {{{h.x, -h.y, h.z}, {0, 0, -2 * h.z}, {0, 2 * h.y, 0}},    // +X
                                 {{-h.x, -h.y, -h.z}, {0, 0, 2 * h.z}, {0, 2 * h.y, 0}},   // -X
                                 {{-h.x, h.y, h.z}, {2 * h.x, 0, 0}, {0, 0, -2 * h.z}},    // +Y
                                 {{-h.x, -h.y, -h.z}, {2 * h.x, 0, 0}, {0, 0, 2 * h.z}},   // -Y
                                 {{-h.x, -h.y, h.z}, {2 * h.x, 0, 0}, {0, 2 * h.y, 0}},    // +Z
                                 {{h.x, -h.y, -h.z}, {-2 * h.x, 0, 0}, {0, 2 * h.y, 0}}};  // -Z
  Primitive p;
  p.material = material;
  for (const auto& face : faces) append(p, quad(face[0], face[1], face[2], material, cells));
  return p;
}

Primitive lathe(const std::vector<ProfilePoint>& profile, uint32_t segments, uint32_t material) {
  Primitive p;
  p.material = material;
  const uint32_t rows = static_cast<uint32_t>(profile.size());
  for (uint32_t i = 0; i < rows; ++i) {
    const glm::vec2 t = profile_tangent(profile, i);
    const glm::vec2 n2 = glm::normalize(glm::vec2(t.y, -t.x));  // outward in the (r, y) plane
    for (uint32_t j = 0; j <= segments; ++j) {                  // j == segments duplicates the seam
      const float phi = 2.0f * 3.14159265358979f * fraction(j % segments, segments);
      const float c = std::cos(phi);
      const float s = std::sin(phi);
      push_vertex(p, {profile[i].x * c, profile[i].y, profile[i].x * s}, {n2.x * c, n2.y, n2.x * s},
                  {fraction(j, segments), fraction(i, rows - 1)});
    }
  }
  for (uint32_t i = 0; i + 1 < rows; ++i) {
    if (profile[i] == profile[i + 1]) continue;  // hard-edge duplicate: no surface between
    for (uint32_t j = 0; j < segments; ++j) {
      const uint32_t a = i * (segments + 1) + j;
      const uint32_t b = a + 1;
      const uint32_t d = a + segments + 1;
      const uint32_t c = d + 1;
      // Skip the triangle that collapses where the profile touches the axis.
      if (profile[i + 1].x != 0.0f) push_triangle(p, a, d, c);
      if (profile[i].x != 0.0f) push_triangle(p, a, c, b);
    }
  }
  return p;
}

Primitive uv_sphere(float radius, uint32_t segments, uint32_t rings, uint32_t material) {
  std::vector<ProfilePoint> profile;
  for (uint32_t k = 0; k <= rings; ++k) {
    const float theta = 3.14159265358979f * fraction(k, rings);
    profile.emplace_back(k == 0 || k == rings ? 0.0f : radius * std::sin(theta),
                         -radius * std::cos(theta));
  }
  Primitive p = lathe(profile, segments, material);
  for (size_t v = 0; v < p.positions.size(); ++v) p.normals[v] = glm::normalize(p.positions[v]);
  return p;
}

std::vector<Primitive> cornell_walls(uint32_t white, uint32_t red, uint32_t green) {
  // Walls face into the box: cross(u, v) points inwards.
  std::vector<Primitive> room;
  room.push_back(quad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, white));  // floor, +Y
  room.push_back(quad({-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, white));  // ceiling, -Y
  room.push_back(quad({-1, 0, -1}, {2, 0, 0}, {0, 2, 0}, white));  // back wall, +Z
  room.push_back(quad({-1, 0, 1}, {0, 0, -2}, {0, 2, 0}, red));    // left wall, +X
  room.push_back(quad({1, 0, -1}, {0, 0, 2}, {0, 2, 0}, green));   // right wall, -X
  return room;
}

Primitive cylinder(float radius, float height, uint32_t segments, uint32_t material) {
  return lathe({{0, 0}, {radius, 0}, {radius, 0}, {radius, height}, {radius, height}, {0, height}},
               segments, material);
}

Primitive grid_from_heights(float size, uint32_t n, uint32_t material,
                            const std::vector<float>& heights) {
  Primitive p;
  p.material = material;
  for (uint32_t j = 0; j < n; ++j) {
    for (uint32_t i = 0; i < n; ++i) {
      const glm::vec2 uv(fraction(i, n - 1), fraction(j, n - 1));
      p.positions.emplace_back((uv.x - 0.5f) * size, heights[j * n + i], (uv.y - 0.5f) * size);
      p.uvs.push_back(uv);
    }
  }
  for (uint32_t j = 0; j + 1 < n; ++j) {
    for (uint32_t i = 0; i + 1 < n; ++i) {
      const uint32_t a = j * n + i;
      const uint32_t d = a + n;  // +z neighbour; with x to the right, (a, d, a+1) faces +Y
      push_triangle(p, a, d, d + 1);
      push_triangle(p, a, d + 1, a + 1);
    }
  }
  p.normals = area_weighted_normals(p.positions, p.indices);
  return p;
}

Primitive leaf_cards(uint32_t count, uint32_t per_ring, float y0, float step, float size, float radius,
                     uint32_t material, uint64_t seed) {
  Primitive cards;
  cards.material = material;
  Pcg32 rng(seed);
  for (uint32_t k = 0; k < count; ++k) {
    const uint32_t ring = k / per_ring;
    const float angle = 2.0f * 3.14159265358979f * (fraction(k % per_ring, per_ring) + 0.37f * float(ring)) +
                        rng.uniform(-0.2f, 0.2f);
    const float tilt = rng.uniform(-0.5f, 0.5f);
    const glm::vec3 out(std::cos(angle), 0.0f, std::sin(angle));
    const glm::vec3 u = size * glm::vec3(-out.z, 0.0f, out.x);
    const glm::vec3 v = size * glm::normalize(glm::vec3(0.0f, 1.0f, 0.0f) + tilt * out);
    append(cards, quad(radius * out + glm::vec3(0.0f, y0 + step * float(ring), 0.0f) - 0.5f * u, u, v, material));
  }
  return cards;
}

Primitive wall_with_openings(const glm::vec3& origin, const glm::vec3& u_dir, const glm::vec3& v_dir, float width,
                             float height, const std::vector<Opening>& openings, float depth, uint32_t material) {
  // Cut the wall along every opening's edges; keep the cells no opening covers.
  std::vector<float> s_cuts{0.0f, width}, t_cuts{0.0f, height};
  for (const Opening& o : openings) {
    s_cuts.insert(s_cuts.end(), {o.s0, o.s1});
    t_cuts.insert(t_cuts.end(), {o.t0, o.t1});
  }
  for (auto* cuts : {&s_cuts, &t_cuts}) {
    std::sort(cuts->begin(), cuts->end());
    cuts->erase(std::unique(cuts->begin(), cuts->end()), cuts->end());
  }
  auto at = [&](float s, float t) { return origin + s * u_dir + t * v_dir; };
  Primitive wall;
  wall.material = material;
  for (size_t i = 0; i + 1 < s_cuts.size(); ++i) {
    for (size_t j = 0; j + 1 < t_cuts.size(); ++j) {
      const float s = 0.5f * (s_cuts[i] + s_cuts[i + 1]), t = 0.5f * (t_cuts[j] + t_cuts[j + 1]);
      const bool open = std::any_of(openings.begin(), openings.end(),
                                    [&](const Opening& o) { return s > o.s0 && s < o.s1 && t > o.t0 && t < o.t1; });
      if (open) continue;
      Primitive cell = quad(at(s_cuts[i], t_cuts[j]), (s_cuts[i + 1] - s_cuts[i]) * u_dir,
                            (t_cuts[j + 1] - t_cuts[j]) * v_dir, material);
      for (glm::vec2& uv : cell.uvs)
        uv = {s_cuts[i] + uv.x * (s_cuts[i + 1] - s_cuts[i]), t_cuts[j] + uv.y * (t_cuts[j + 1] - t_cuts[j])};
      append(wall, cell);
    }
  }
  // The reveals: sill (facing v), lintel (-v), jambs (u at s0, -u at s1); `back` points away from
  // the wall's face.
  const glm::vec3 back = -depth * glm::normalize(glm::cross(u_dir, v_dir));
  for (const Opening& o : openings) {
    const glm::vec3 w = (o.s1 - o.s0) * u_dir, h = (o.t1 - o.t0) * v_dir;
    for (Primitive side : {quad(at(o.s0, o.t0), w, back, material), quad(at(o.s0, o.t1), back, w, material),
                           quad(at(o.s0, o.t0), back, h, material), quad(at(o.s1, o.t0), h, back, material)}) {
      append(wall, side);
    }
  }
  return wall;
}

Primitive with_planar_uvs(Primitive p, const glm::vec3& u_dir, const glm::vec3& v_dir) {
  for (size_t v = 0; v < p.positions.size(); ++v)
    p.uvs[v] = {glm::dot(p.positions[v], u_dir), glm::dot(p.positions[v], v_dir)};
  return p;
}

Primitive transformed(Primitive p, const glm::mat4& m) {
  const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(m)));
  for (glm::vec3& position : p.positions) position = glm::vec3(m * glm::vec4(position, 1.0f));
  for (glm::vec3& normal : p.normals) normal = glm::normalize(normal_matrix * normal);
  return p;
}

void append(Primitive& a, const Primitive& b) {
  const uint32_t base = static_cast<uint32_t>(a.positions.size());
  a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
  a.normals.insert(a.normals.end(), b.normals.begin(), b.normals.end());
  a.uvs.insert(a.uvs.end(), b.uvs.begin(), b.uvs.end());
  for (uint32_t index : b.indices) a.indices.push_back(base + index);
}

}  // namespace strata::scene::builtin
