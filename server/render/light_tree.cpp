#include "render/light_tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>

namespace strata::render {
namespace {

constexpr float k_pi = std::numbers::pi_v<float>;

// The orientation cone of a set of emitters: every normal within theta_o of `axis`, each emitting
// up to theta_e from its normal.
struct Cone {
  glm::vec3 axis{0.0f, 0.0f, 1.0f};
  float theta_o = 0.0f;
  float theta_e = 0.0f;
};

// The least cone holding both (Conty Estevez & Kulla 2018, Alg. 1): the wider one if it holds the
// other, else the cone spanning both, its axis turned from the wider one's towards the other's.
Cone merge(Cone a, Cone b) {
  if (a.theta_o < b.theta_o) std::swap(a, b);
  const float theta_e = std::max(a.theta_e, b.theta_e);
  const float theta_d = std::acos(std::clamp(glm::dot(a.axis, b.axis), -1.0f, 1.0f));
  if (std::min(theta_d + b.theta_o, k_pi) <= a.theta_o) return {a.axis, a.theta_o, theta_e};
  const float theta_o = 0.5f * (a.theta_o + theta_d + b.theta_o);
  if (theta_o >= k_pi) return {a.axis, k_pi, theta_e};
  const glm::vec3 k = glm::cross(a.axis, b.axis);
  const float k_len = glm::length(k);
  if (!(k_len > 1e-7f)) return {a.axis, k_pi, theta_e};  // opposite axes
  const float turn = theta_o - a.theta_o;
  const glm::vec3 kn = k / k_len;  // a.axis turned by `turn` about kn (Rodrigues; kn is normal to it)
  const glm::vec3 axis = glm::normalize(a.axis * std::cos(turn) + glm::cross(kn, a.axis) * std::sin(turn));
  return {axis, theta_o, theta_e};
}

// The solid-angle measure of a cone's emission (Conty Estevez & Kulla 2018, Eq. 1): the integral
// over directions within theta_o + theta_e of the axis of the cosine past theta_o.
double orientation_measure(const Cone& c) {
  const double o = c.theta_o;
  const double w = std::min<double>(c.theta_o + c.theta_e, std::numbers::pi);
  return 2.0 * std::numbers::pi * (1.0 - std::cos(o)) +
         0.5 * std::numbers::pi * (2.0 * w * std::sin(o) - std::cos(o - 2.0 * w) - 2.0 * o * std::sin(o) + std::cos(o));
}

struct Bounds {
  glm::vec3 lo{std::numeric_limits<float>::max()};
  glm::vec3 hi{-std::numeric_limits<float>::max()};
  double power = 0.0;
  Cone cone;
  bool two_sided = false;
  bool empty = true;

  void add(const Bounds& o) {
    if (o.empty) return;
    lo = glm::min(lo, o.lo);
    hi = glm::max(hi, o.hi);
    power += o.power;
    cone = empty ? o.cone : merge(cone, o.cone);
    two_sided = two_sided || o.two_sided;
    empty = false;
  }
  // A size that tells apart sets of points too: the box's surface area plus its squared diagonal.
  double size() const {
    if (empty) return 0.0;
    const glm::dvec3 e = glm::dvec3(hi - lo);
    return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x) + glm::dot(e, e);
  }
  double cost() const { return empty ? 0.0 : power * orientation_measure(cone) * size(); }
};

struct Item {
  Bounds bounds;
  glm::vec3 centroid;
  uint32_t entry;
};

class Builder {
 public:
  explicit Builder(LightTree& tree) : tree_(tree) {}

  // Writes the subtree of items[begin, end) depth-first and returns its root's index.
  uint32_t build(std::vector<Item>& items, size_t begin, size_t end, uint32_t depth, uint64_t trail) {
    Bounds all;
    for (size_t i = begin; i < end; ++i) all.add(items[i].bounds);
    const uint32_t index = uint32_t(tree_.nodes.size());
    tree_.nodes.push_back(node_of(all));
    if (end - begin == 1) {
      const uint32_t entry = items[begin].entry;
      tree_.nodes[index].links.x = entry;
      tree_.nodes[index].links.y = gpu::LIGHT_NODE_LEAF | flags_of(all);
      tree_.trails[entry] = glm::uvec4(uint32_t(trail), uint32_t(trail >> 32), depth, 0u);
      return index;
    }
    const size_t mid = split(items, begin, end, depth);
    build(items, begin, mid, depth + 1, trail);
    const uint32_t second = build(items, mid, end, depth + 1, trail | (uint64_t(1) << depth));
    tree_.nodes[index].links.x = second;
    tree_.nodes[index].links.y = flags_of(all);
    return index;
  }

 private:
  static uint32_t flags_of(const Bounds& b) { return b.two_sided ? gpu::LIGHT_NODE_TWO_SIDED : 0u; }

  static gpu::GpuLightNode node_of(const Bounds& b) {
    gpu::GpuLightNode n{};
    n.lo_power = glm::vec4(b.lo, float(b.power));
    n.hi_cos_o = glm::vec4(b.hi, std::cos(b.cone.theta_o));
    n.axis_cos_e = glm::vec4(b.cone.axis, std::cos(b.cone.theta_e));
    const float sin_o = std::sin(b.cone.theta_o);
    std::memcpy(&n.links.z, &sin_o, sizeof sin_o);
    return n;
  }

  // Where items[begin, end) splits: the least-cost bin boundary over the three axes, else (no
  // spread of centroids, or past depth 40) the median along the widest axis.
  size_t split(std::vector<Item>& items, size_t begin, size_t end, uint32_t depth) {
    constexpr int k_bins = 12;
    glm::vec3 clo(std::numeric_limits<float>::max()), chi(-std::numeric_limits<float>::max());
    for (size_t i = begin; i < end; ++i) {
      clo = glm::min(clo, items[i].centroid);
      chi = glm::max(chi, items[i].centroid);
    }
    const glm::vec3 extent = chi - clo;
    double best = std::numeric_limits<double>::infinity();
    int best_axis = -1, best_bin = 0;
    if (depth < 40) {
      for (int axis = 0; axis < 3; ++axis) {
        if (!(extent[axis] > 0.0f)) continue;
        std::array<Bounds, k_bins> bins;
        for (size_t i = begin; i < end; ++i) bins[size_t(bin_of(items[i], clo, extent, axis, k_bins))].add(items[i].bounds);
        for (int b = 1; b < k_bins; ++b) {
          Bounds below, above;
          for (int k = 0; k < b; ++k) below.add(bins[size_t(k)]);
          for (int k = b; k < k_bins; ++k) above.add(bins[size_t(k)]);
          if (below.empty || above.empty) continue;
          const double c = below.cost() + above.cost();
          if (c < best) {
            best = c;
            best_axis = axis;
            best_bin = b;
          }
        }
      }
    }
    if (best_axis >= 0) {
      auto it = std::partition(items.begin() + ptrdiff_t(begin), items.begin() + ptrdiff_t(end),
                               [&](const Item& i) { return bin_of(i, clo, extent, best_axis, k_bins) < best_bin; });
      return size_t(it - items.begin());
    }
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const size_t mid = begin + (end - begin) / 2;
    std::nth_element(items.begin() + ptrdiff_t(begin), items.begin() + ptrdiff_t(mid), items.begin() + ptrdiff_t(end),
                     [axis](const Item& a, const Item& b) { return a.centroid[axis] < b.centroid[axis]; });
    return mid;
  }

  static int bin_of(const Item& i, glm::vec3 clo, glm::vec3 extent, int axis, int bins) {
    const int b = int(float(bins) * (i.centroid[axis] - clo[axis]) / extent[axis]);
    return std::clamp(b, 0, bins - 1);
  }

  LightTree& tree_;
};

Item emitter_item(const gpu::GpuEmitter& e, double power, uint32_t entry) {
  const glm::vec3 p0(e.p0_area), p1(e.p1_pmf), p2(e.p2_flags);
  uint32_t flags;
  std::memcpy(&flags, &e.p2_flags.w, sizeof flags);
  Item it{};
  it.bounds.lo = glm::min(p0, glm::min(p1, p2));
  it.bounds.hi = glm::max(p0, glm::max(p1, p2));
  it.bounds.power = power;
  const glm::vec3 c = glm::cross(p1 - p0, p2 - p0);
  it.bounds.cone = {glm::length(c) > 0.0f ? glm::normalize(c) : glm::vec3(0, 0, 1), 0.0f, 0.5f * k_pi};
  it.bounds.two_sided = (flags & gpu::MATERIAL_DOUBLE_SIDED) != 0u;
  it.bounds.empty = false;
  it.centroid = (p0 + p1 + p2) / 3.0f;
  it.entry = entry;
  return it;
}

Item punctual_item(const gpu::GpuPunctualLight& l, const scene::Light& light, double power, uint32_t entry) {
  Item it{};
  const glm::vec3 p(l.position_range);
  it.bounds.lo = it.bounds.hi = it.centroid = p;
  it.bounds.power = power;
  if (light.type == scene::LightType::kSpot)
    it.bounds.cone = {glm::normalize(glm::vec3(l.direction_type)), 0.0f, std::min(light.outer_cone, 0.5f * k_pi)};
  else
    it.bounds.cone = {glm::vec3(0, 0, 1), k_pi, 0.5f * k_pi};
  it.bounds.empty = false;
  it.entry = entry;
  return it;
}

}  // namespace

LightTree build_light_tree(const EmitterTable& table, std::span<const scene::Light> lights, uint32_t instance_count) {
  LightTree t;
  const uint32_t emitters = uint32_t(table.emitters.size());
  t.entry_count = emitters + uint32_t(table.lights.size());
  t.trails.assign(t.entry_count, glm::uvec4(0u, 0u, gpu::LIGHT_TREE_NONE, 0u));
  std::vector<Item> items;
  double directional_power = 0.0, total = 0.0;
  for (uint32_t e = 0; e < t.entry_count; ++e) {
    const double power = table.power.at(e);
    if (!(power > 0.0)) continue;
    total += power;
    if (e < emitters) {
      items.push_back(emitter_item(table.emitters[e], power, e));
    } else if (lights[e - emitters].type == scene::LightType::kDirectional) {
      t.directional.push_back(glm::uvec2(e, 0u));
      directional_power += power;
    } else {
      items.push_back(punctual_item(table.lights[e - emitters], lights[e - emitters], power, e));
    }
  }
  for (auto& d : t.directional) {
    const float p = float(table.power[d.x] / directional_power);
    std::memcpy(&d.y, &p, sizeof p);
  }
  t.directional_prob = items.empty() ? (t.directional.empty() ? 0.0f : 1.0f) : float(directional_power / total);
  if (!items.empty()) Builder(t).build(items, 0, items.size(), 0, 0);

  // The emitter entries of each instance and geometry (the table lists them instance by instance,
  // geometry by geometry, triangles ascending).
  t.instances.assign(instance_count, glm::uvec2(0u));
  for (uint32_t e = 0; e < emitters;) {
    const uint32_t instance = table.emitters[e].surface.x;
    const uint32_t first_record = uint32_t(t.geometries.size());
    uint32_t geometries = 0;
    while (e < emitters && table.emitters[e].surface.x == instance) {
      const uint32_t g = table.emitters[e].surface.y;
      while (geometries <= g) {
        t.geometries.push_back(glm::uvec2(e, 0u));
        ++geometries;
      }
      t.geometries.back().y += 1;
      t.triangles.push_back(table.emitters[e].surface.z);
      ++e;
    }
    t.instances.at(instance) = glm::uvec2(first_record, geometries);
  }
  return t;
}

uint32_t LightTree::entry_of(uint32_t instance, uint32_t geometry, uint32_t triangle) const {
  if (instance >= instances.size() || geometry >= instances[instance].y) return gpu::LIGHT_TREE_NONE;
  const glm::uvec2 g = geometries[instances[instance].x + geometry];
  const auto first = triangles.begin() + g.x, last = first + g.y;
  const auto it = std::lower_bound(first, last, triangle);
  return it != last && *it == triangle ? uint32_t(it - triangles.begin()) : gpu::LIGHT_TREE_NONE;
}

std::vector<std::byte> LightTree::bytes() const {
  gpu::GpuLightTreeHeader h{};
  h.node_count = uint32_t(nodes.size());
  h.entry_count = entry_count;
  h.directional_count = uint32_t(directional.size());
  h.instance_count = uint32_t(instances.size());
  h.directional_prob = directional_prob;
  std::vector<std::byte> out;
  auto append = [&out](const void* data, size_t size) {
    const uint32_t offset = uint32_t(out.size());
    out.resize(offset + (size + 15) / 16 * 16);
    if (size) std::memcpy(out.data() + offset, data, size);
    return offset;
  };
  append(&h, sizeof h);
  h.nodes_offset = append(nodes.data(), nodes.size() * sizeof nodes[0]);
  h.trails_offset = append(trails.data(), trails.size() * sizeof trails[0]);
  h.directional_offset = append(directional.data(), directional.size() * sizeof directional[0]);
  h.instances_offset = append(instances.data(), instances.size() * sizeof instances[0]);
  h.geometries_offset = append(geometries.data(), geometries.size() * sizeof geometries[0]);
  h.triangles_offset = append(triangles.data(), triangles.size() * sizeof triangles[0]);
  std::memcpy(out.data(), &h, sizeof h);
  return out;
}

}  // namespace strata::render

// sampling/light_tree.h over the host's arrays.
#define LIGHT_TREE_T const ::strata::render::LightTree&
#define LIGHT_TREE_NODE(tree, i) (tree).nodes[i]
#define LIGHT_TREE_TRAIL(tree, e) (tree).trails[e]
#define LIGHT_TREE_NODE_COUNT(tree) uint32_t((tree).nodes.size())

#include "sampling/light_tree.h"

namespace strata::render {

bool light_tree_choose(const LightTree& tree, glm::vec3 x, glm::vec4 receiver, float u, uint32_t& entry, float& pmf) {
  return gpu::light_tree_choose(tree, x, receiver, u, entry, pmf);
}

float light_tree_pmf(const LightTree& tree, glm::vec3 x, glm::vec4 receiver, uint32_t entry) {
  return gpu::light_tree_pmf(tree, x, receiver, entry);
}

}  // namespace strata::render
