#pragma once
// An independent CPU reference for the GPU path tracer. It shares no code with shaders/: double
// precision, brute-force intersection, BSDF sampling only (no next-event estimation, no MIS), so a
// bug in the GPU's light sampling or ray queries cannot cancel out in a comparison.
//
// Only Lambert scenes are supported (every material has metallic == 0; roughness is ignored). The
// camera model, the ray offsets and the face conventions are those of the GPU renderer:
//   - pixel (x, y), y = 0 is the top row, jitter (u, v) in [0,1)^2 (box filter);
//   - front faces wind counter-clockwise in object space (a mirroring transform keeps the front);
//   - emitters emit from the front face, or both faces when the material is double-sided;
//   - a bounce starts at the hit point with t_min = 1e-4 * (1 + max |coordinate|) and skips the
//     triangle it leaves.
// Lambert sampling uses the interpolated shading normal turned to the side the ray arrived from;
// a sampled direction below the geometric surface ends the path (no light leaks through it).
// Alpha-tested materials (MASK, and BLEND as the device renders it: MASK at 0.5) let rays through
// where their coverage, alpha x the base colour texture's alpha at its finest level (the sampler's
// magnification filter and wrap modes, KHR_texture_transform applied), is under the cutoff.
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace strata::test {

// One world-space triangle with where it came from.
struct CpuTriangle {
  glm::dvec3 p0, p1, p2;
  glm::dvec3 n0, n1, n2;     // world shading normals (unit)
  glm::dvec3 ng;             // unit geometric normal on the front side
  uint32_t instance = 0;     // index into Scene::instances
  uint32_t primitive = 0;    // index within the mesh used at this frame's LoD
  uint32_t triangle = 0;     // index within the primitive
  uint32_t material = 0;
  glm::dvec2 uv0{0.0}, uv1{0.0}, uv2{0.0};  // the texCoords the material's base colour texture reads
};

struct CpuScene {
  std::vector<CpuTriangle> triangles;
  std::vector<scene::Material> materials;
  scene::Environment environment;
  scene::TextureSet textures;
};

// Throws std::invalid_argument when the frame state does not fit the scene (array lengths, LoD
// levels, mesh, material or vertex indices out of range).
CpuScene build_cpu_scene(const scene::Scene& scene, const scene::FrameState& frame);

struct CpuRay {
  glm::dvec3 origin{0.0};
  glm::dvec3 direction{0.0, 0.0, -1.0};  // need not be unit length; t is in its units
  double t_min = 0.0;
  double t_max = std::numeric_limits<double>::infinity();
  // Index into CpuScene::triangles of a triangle to ignore (the one a bounce leaves), or none.
  std::optional<size_t> ignore;
};

struct CpuHit {
  double t = 0.0;
  uint32_t instance = 0;
  uint32_t primitive = 0;
  uint32_t triangle = 0;
  double u = 0.0;  // barycentrics of p1 and p2: p = (1-u-v) p0 + u p1 + v p2 (Vulkan's convention)
  double v = 0.0;
  glm::dvec3 geometric_normal{0.0};  // unit, front side
  size_t scene_triangle = 0;         // index into CpuScene::triangles
};

// Closest hit with t_min < t < t_max on either face (Möller–Trumbore in double precision).
std::optional<CpuHit> intersect(const CpuScene& scene, const CpuRay& ray);

// The primary ray through pixel (x, y) at jitter (u, v) of a width x height pinhole camera.
CpuRay camera_ray(const scene::Camera& camera, uint32_t width, uint32_t height, uint32_t x,
                  uint32_t y, double u, double v);

struct MeanEstimate {
  glm::dvec3 mean{0.0};       // mean radiance over the image, per channel
  glm::dvec3 std_error{0.0};  // standard error of `mean`, from the variance over all paths
  uint64_t paths = 0;
};

// Paths end after this many surface vertices. The cut loses about albedo^max_depth of the energy,
// so a GPU comparison on bright, closed scenes should use the GPU's own limit.
inline constexpr uint32_t kDefaultMaxDepth = 64;

// Mean image radiance by path tracing with samples_per_pixel paths per pixel. Deterministic for a
// given seed: every path has its own random stream, and partial sums are combined in a fixed order
// whatever the number of threads. Throws std::invalid_argument for non-Lambert materials, a thin
// lens camera, or a zero size, sample count or depth.
MeanEstimate estimate_image_mean(const scene::Scene& scene, const scene::FrameState& frame,
                                 uint32_t width, uint32_t height, uint32_t samples_per_pixel,
                                 uint64_t seed, uint32_t max_depth = kDefaultMaxDepth);

}  // namespace strata::test
