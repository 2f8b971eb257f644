#include "support/cpu_tracer.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <stdexcept>
#include <string>
#include <thread>

#include <glm/gtc/quaternion.hpp>

#include "scene/deform.h"
#include "scene/environment_map.h"

namespace strata::test {
namespace {

constexpr uint32_t kRouletteDepth = 3;  // Russian roulette from the fourth vertex on
constexpr double kMaxSurvival = 0.95;
constexpr double kOffsetScale = 1e-4;

[[noreturn]] void fail(const std::string& message) {
  throw std::invalid_argument("cpu_tracer: " + message);
}

// PCG32 (O'Neill, pcg-random.org, XSH RR output). Each path gets its own generator, so results do
// not depend on which thread traced the path.
class Pcg32 {
 public:
  Pcg32(uint64_t seed, uint64_t stream) : inc_((stream << 1u) | 1u) {
    next();
    state_ += seed;
    next();
  }
  uint32_t next() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    const auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((0u - rot) & 31u));
  }
  double uniform() {  // [0, 1) with 53 random bits
    const uint64_t bits = (uint64_t(next()) << 32 | next()) >> 11;
    return double(bits) * 0x1p-53;
  }

 private:
  uint64_t state_ = 0;
  uint64_t inc_;
};

// SplitMix64 finaliser: decorrelates the per-path seeds derived from consecutive path indices.
uint64_t mix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// Welford's running mean and sum of squared deviations, mergeable (Chan et al.). Constant inputs
// give exactly that constant and zero deviation, which the exact-value tests rely on.
struct RunningStats {
  uint64_t n = 0;
  glm::dvec3 mean{0.0};
  glm::dvec3 m2{0.0};
  void add(const glm::dvec3& x) {
    ++n;
    const glm::dvec3 d = x - mean;
    mean += d / double(n);
    m2 += d * (x - mean);
  }
  void merge(const RunningStats& o) {
    if (o.n == 0) return;
    if (n == 0) {
      *this = o;
      return;
    }
    const double na = double(n), nb = double(o.n), total = na + nb;
    const glm::dvec3 d = o.mean - mean;
    mean += d * (nb / total);
    m2 += o.m2 + d * d * (na * nb / total);
    n += o.n;
  }
};

// Cosine-weighted direction about unit n; the orthonormal basis is Duff et al. (JCGT 2017).
glm::dvec3 sample_cosine(const glm::dvec3& n, double u1, double u2) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double b = n.x * n.y * a;
  const glm::dvec3 t(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const glm::dvec3 s(b, sign + n.y * n.y * a, -n.y);
  const double r = std::sqrt(u1);
  const double phi = 2.0 * glm::pi<double>() * u2;
  return glm::normalize(r * std::cos(phi) * t + r * std::sin(phi) * s +
                        std::sqrt(std::max(0.0, 1.0 - u1)) * n);
}

double max_abs(const glm::dvec3& p) {
  return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
}

glm::dvec3 trace_path(const CpuScene& scene, CpuRay ray, uint32_t max_depth, Pcg32& rng) {
  glm::dvec3 radiance(0.0);
  glm::dvec3 throughput(1.0);
  for (uint32_t depth = 0; depth < max_depth; ++depth) {
    const std::optional<CpuHit> hit = intersect(scene, ray);
    if (!hit) {
      const glm::vec3 sky = scene.environment.map ? scene::environment_radiance(*scene.environment.map, glm::vec3(ray.direction))
                                                  : scene.environment.radiance;
      radiance += throughput * glm::dvec3(sky);
      break;
    }
    const CpuTriangle& tri = scene.triangles[hit->scene_triangle];
    const scene::Material& material = scene.materials[tri.material];
    const bool front = glm::dot(ray.direction, tri.ng) < 0.0;
    if (front || material.double_sided) radiance += throughput * glm::dvec3(material.emission);

    const glm::dvec3 albedo(material.base_color);
    if (depth >= kRouletteDepth) {
      const double survival = std::min(std::max({albedo.x, albedo.y, albedo.z}), kMaxSurvival);
      if (rng.uniform() >= survival) break;
      throughput /= survival;
    }
    // Both faces scatter: turn the normals to the side the ray came from.
    const glm::dvec3 ng = front ? tri.ng : -tri.ng;
    const double w = 1.0 - hit->u - hit->v;
    glm::dvec3 ns = w * tri.n0 + hit->u * tri.n1 + hit->v * tri.n2;
    const double ns_length = glm::length(ns);
    ns = ns_length > 1e-12 ? ns / ns_length : tri.ng;
    if (!front) ns = -ns;
    if (glm::dot(ns, ng) <= 0.0) ns = ng;  // inconsistent shading normal: trust the geometry
    const double u1 = rng.uniform();
    const double u2 = rng.uniform();
    const glm::dvec3 wi = sample_cosine(ns, u1, u2);
    if (glm::dot(wi, ng) <= 0.0) break;
    // Lambert with cosine sampling: f cos / pdf = albedo.
    throughput *= albedo;

    const glm::dvec3 p = w * tri.p0 + hit->u * tri.p1 + hit->v * tri.p2;
    ray = CpuRay{p, wi, kOffsetScale * (1.0 + max_abs(p)), std::numeric_limits<double>::infinity(),
                 hit->scene_triangle};
  }
  return radiance;
}

RunningStats trace_row(const CpuScene& scene, const scene::Camera& camera, uint32_t width,
                       uint32_t height, uint32_t y, uint32_t spp, uint64_t seed,
                       uint32_t max_depth) {
  RunningStats stats;
  for (uint32_t x = 0; x < width; ++x) {
    for (uint32_t s = 0; s < spp; ++s) {
      const uint64_t path = (uint64_t(y) * width + x) * spp + s;
      Pcg32 rng(mix64(seed ^ mix64(path)), path);
      const double u = rng.uniform();
      const double v = rng.uniform();
      stats.add(trace_path(scene, camera_ray(camera, width, height, x, y, u, v), max_depth, rng));
    }
  }
  return stats;
}

}  // namespace

CpuScene build_cpu_scene(const scene::Scene& scene, const scene::FrameState& frame) {
  if (frame.transforms.size() != scene.instances.size() ||
      frame.lods.size() != scene.instances.size()) {
    fail("frame state has " + std::to_string(frame.transforms.size()) + " transforms and " +
         std::to_string(frame.lods.size()) + " LoD levels for " +
         std::to_string(scene.instances.size()) + " instances");
  }
  CpuScene out{{}, scene.materials, scene.environment, scene.textures};
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const scene::Instance& instance = scene.instances[i];
    if (frame.lods[i] >= instance.lod_meshes.size() ||
        instance.lod_meshes[frame.lods[i]] >= scene.meshes.size()) {
      fail("instance " + std::to_string(i) + ": LoD level or mesh index out of range");
    }
    const scene::Mesh& mesh = scene.meshes[instance.lod_meshes[frame.lods[i]]];
    const glm::dmat4 m(frame.transforms[i]);
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(glm::dmat3(m)));
    // A mirroring transform reverses the world-space winding; the front face stays the object's.
    const double orientation = glm::determinant(glm::dmat3(m)) < 0.0 ? -1.0 : 1.0;
    // A skinned or morphing instance's vertices as the frame poses them (scene/deform.h).
    const std::vector<scene::SkinningMatrix> skinning =
        instance.deforms() ? scene::instance_skinning(scene, frame, i) : std::vector<scene::SkinningMatrix>{};
    for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
      const scene::Primitive& rest = mesh.primitives[pi];
      scene::Primitive posed;
      if (instance.deforms()) {
        posed = rest;
        scene::DeformedVertices d = scene::deform_primitive(rest, skinning, scene::morph_weights_at(scene, frame, i));
        posed.positions = std::move(d.positions);
        posed.normals = std::move(d.normals);
      }
      const scene::Primitive& prim = instance.deforms() ? posed : rest;
      const bool has_normals = !prim.normals.empty();
      if (prim.material >= scene.materials.size() || prim.indices.size() % 3 != 0 ||
          (has_normals && prim.normals.size() != prim.positions.size())) {
        fail("instance " + std::to_string(i) + " primitive " + std::to_string(pi) +
             ": material index, index count or normal count is invalid");
      }
      for (size_t ti = 0; ti < prim.triangle_count(); ++ti) {
        CpuTriangle tri;
        glm::dvec3* positions[3] = {&tri.p0, &tri.p1, &tri.p2};
        glm::dvec3* normals[3] = {&tri.n0, &tri.n1, &tri.n2};
        for (size_t k = 0; k < 3; ++k) {
          const uint32_t index = prim.indices[3 * ti + k];
          if (index >= prim.positions.size()) {
            fail("instance " + std::to_string(i) + " primitive " + std::to_string(pi) +
                 ": vertex index " + std::to_string(index) + " out of range");
          }
          *positions[k] = glm::dvec3(m * glm::dvec4(glm::dvec3(prim.positions[index]), 1.0));
          if (has_normals) *normals[k] = normal_matrix * glm::dvec3(prim.normals[index]);
        }
        const glm::dvec3 cross = glm::cross(tri.p1 - tri.p0, tri.p2 - tri.p0);
        const double area2 = glm::length(cross);
        if (!(area2 > 0.0)) continue;  // degenerate: a ray can never hit it
        tri.ng = orientation * cross / area2;
        for (glm::dvec3* n : normals) {
          const double length = glm::length(*n);
          *n = has_normals && length > 0.0 ? *n / length : tri.ng;
        }
        tri.instance = static_cast<uint32_t>(i);
        tri.primitive = static_cast<uint32_t>(pi);
        tri.triangle = static_cast<uint32_t>(ti);
        tri.material = prim.material;
        const scene::Material& mat = scene.materials[prim.material];
        const bool set1 = mat.base_color_texture.tex_coord == 1 && !prim.uvs1.empty();
        const std::vector<glm::vec2>& uvs = set1 ? prim.uvs1 : prim.uvs;
        if (uvs.size() == prim.positions.size()) {
          tri.uv0 = glm::dvec2(uvs[prim.indices[3 * ti]]);
          tri.uv1 = glm::dvec2(uvs[prim.indices[3 * ti + 1]]);
          tri.uv2 = glm::dvec2(uvs[prim.indices[3 * ti + 2]]);
        }
        out.triangles.push_back(tri);
      }
    }
  }
  return out;
}

namespace {

int wrap_index(int64_t i, int n, scene::TextureWrap mode) {
  if (mode == scene::TextureWrap::kClampToEdge) return int(std::clamp<int64_t>(i, 0, n - 1));
  const int64_t m = ((i % (2 * n)) + 2 * n) % (2 * n);
  if (mode == scene::TextureWrap::kMirroredRepeat) return int(m < n ? m : 2 * n - 1 - m);
  return int(m % n);
}

// Whether an alpha-tested triangle is a surface at barycentrics (u, v) (the header's rule).
bool alpha_keeps(const CpuScene& scene, const CpuTriangle& tri, double u, double v) {
  const scene::Material& m = scene.materials[tri.material];
  if (m.alpha_mode == scene::AlphaMode::kOpaque) return true;
  const double cutoff = m.alpha_mode == scene::AlphaMode::kBlend ? 0.5 : double(m.alpha_cutoff);
  double a = m.alpha;
  if (m.base_color_texture.texture >= 0) {
    const scene::Texture& t = scene.textures.textures[size_t(m.base_color_texture.texture)];
    const scene::MipLevel& l = scene.textures.levels[scene.textures.images[t.image].first_level];
    const glm::dvec2 uv0 = (1.0 - u - v) * tri.uv0 + u * tri.uv1 + v * tri.uv2;
    const glm::dvec2 uv = glm::dvec2(glm::dmat3(m.base_color_texture.transform.matrix()) * glm::dvec3(uv0, 1.0));
    auto alpha_at = [&](int64_t x, int64_t y) {
      const int xi = wrap_index(x, int(l.width), t.sampler.wrap_u), yi = wrap_index(y, int(l.height), t.sampler.wrap_v);
      return double(scene.textures.texels[l.offset + size_t(yi) * l.width + size_t(xi)] >> 24) / 255.0;
    };
    const glm::dvec2 p = uv * glm::dvec2(l.width, l.height);
    if (t.sampler.mag_filter == scene::TextureFilter::kNearest) {
      a *= alpha_at(int64_t(std::floor(p.x)), int64_t(std::floor(p.y)));
    } else {
      const glm::dvec2 q = p - 0.5, f = q - glm::floor(q);
      const int64_t x = int64_t(std::floor(q.x)), y = int64_t(std::floor(q.y));
      a *= (1 - f.x) * (1 - f.y) * alpha_at(x, y) + f.x * (1 - f.y) * alpha_at(x + 1, y) + (1 - f.x) * f.y * alpha_at(x, y + 1) +
           f.x * f.y * alpha_at(x + 1, y + 1);
    }
  }
  return a >= cutoff;
}

}  // namespace

std::optional<CpuHit> intersect(const CpuScene& scene, const CpuRay& ray) {
  std::optional<CpuHit> best;
  double t_best = ray.t_max;
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    if (ray.ignore && *ray.ignore == i) continue;
    const CpuTriangle& tri = scene.triangles[i];
    // Möller–Trumbore without culling: both faces are hit.
    const glm::dvec3 e1 = tri.p1 - tri.p0;
    const glm::dvec3 e2 = tri.p2 - tri.p0;
    const glm::dvec3 pvec = glm::cross(ray.direction, e2);
    const double det = glm::dot(e1, pvec);
    if (det == 0.0) continue;  // ray parallel to the plane
    const double inv_det = 1.0 / det;
    const glm::dvec3 tvec = ray.origin - tri.p0;
    const double u = glm::dot(tvec, pvec) * inv_det;
    if (!(u >= 0.0 && u <= 1.0)) continue;
    const glm::dvec3 qvec = glm::cross(tvec, e1);
    const double v = glm::dot(ray.direction, qvec) * inv_det;
    if (!(v >= 0.0 && u + v <= 1.0)) continue;
    const double t = glm::dot(e2, qvec) * inv_det;
    if (!(t > ray.t_min && t < t_best)) continue;
    if (!alpha_keeps(scene, tri, u, v)) continue;
    t_best = t;
    best = CpuHit{t, tri.instance, tri.primitive, tri.triangle, u, v, tri.ng, i};
  }
  return best;
}

CpuRay camera_ray(const scene::Camera& camera, uint32_t width, uint32_t height, uint32_t x,
                  uint32_t y, double u, double v) {
  const double w = double(width);
  const double h = double(height);
  const double ndc_x = (double(x) + u) / w * 2.0 - 1.0;
  const double ndc_y = 1.0 - (double(y) + v) / h * 2.0;
  const double tan_half = std::tan(double(camera.yfov) / 2.0);
  const glm::dvec3 dir_camera =
      glm::normalize(glm::dvec3(ndc_x * tan_half * (w / h), ndc_y * tan_half, -1.0));
  const glm::dvec3 dir_world = glm::normalize(glm::dquat(camera.orientation) * dir_camera);
  return CpuRay{glm::dvec3(camera.position), dir_world};
}

MeanEstimate estimate_image_mean(const scene::Scene& scene, const scene::FrameState& frame,
                                 uint32_t width, uint32_t height, uint32_t samples_per_pixel,
                                 uint64_t seed, uint32_t max_depth) {
  if (width == 0 || height == 0 || samples_per_pixel == 0 || max_depth == 0) {
    fail("image size, samples per pixel and max depth must be positive");
  }
  for (const scene::Material& material : scene.materials) {
    if (material.metallic != 0.0f) {
      fail("material '" + material.name + "' is not Lambert (metallic != 0)");
    }
  }
  if (frame.camera.aperture != 0.0f) fail("only a pinhole camera (aperture 0) is supported");
  const CpuScene cpu = build_cpu_scene(scene, frame);

  // Rows are the unit of work; each row's statistics are kept apart and merged in row order, so
  // the result is bit-identical for any thread count.
  std::vector<RunningStats> rows(height);
  const uint32_t threads = std::clamp(std::thread::hardware_concurrency(), 1u, height);
  std::vector<std::exception_ptr> errors(threads);
  std::vector<std::thread> pool;
  for (uint32_t t = 0; t < threads; ++t) {
    pool.emplace_back([&, t] {
      try {
        for (uint32_t y = t; y < height; y += threads) {
          rows[y] = trace_row(cpu, frame.camera, width, height, y, samples_per_pixel, seed,
                              max_depth);
        }
      } catch (...) {
        errors[t] = std::current_exception();
      }
    });
  }
  for (std::thread& thread : pool) thread.join();
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
  RunningStats total;
  for (const RunningStats& row : rows) total.merge(row);
  MeanEstimate result;
  result.mean = total.mean;
  result.paths = total.n;
  if (total.n > 1) {
    const double n = double(total.n);
    result.std_error = glm::sqrt(total.m2 / (n - 1.0) / n);
  }
  return result;
}

}  // namespace strata::test
