// The packed reservoir (96 bytes) round-trips every field: ids and barycentrics exactly, radiance
// exactly (f32, beyond fp16's range), directions to octahedral snorm16 precision.
#include <gtest/gtest.h>

#include <cmath>

#include "restir/reservoir.h"
#include "sampling/rng.h"
#include "sampling/warp.h"

namespace strata::gpu {
namespace {

Reservoir sample_reservoir(Rng& rng) {
  Reservoir r;
  r.y.x1 = {12345u, 17u, 7654321u, vec2(0.123456789f, 0.5f), 2u};
  r.y.xk = {(1u << SURFACE_INSTANCE_BITS) - 2u, (1u << SURFACE_GEOMETRY_BITS) - 1u, 0xFFFFFFFEu, vec2(1e-7f, 0.9999999f), 15u};
  r.y.xk_direction = sample_uniform_sphere(rng_next_float2(rng));
  r.y.xk_radiance = vec3(1.0e6f, 3.5e-8f, 70000.25f);
  r.y.k = 2u;
  r.y.segments = 9u;
  r.y.flags = SAMPLE_VALID | SAMPLE_NEE;
  r.y.seed = 0xDEADBEEFu;
  r.y.lens = vec2(0.25f, 0.75f);
  r.y.time = 0.5f;
  r.y.jitter = vec2(0.123456789f, 0.987654321f);
  r.y.density = 3.5e-7f;
  r.y.light_pdf_end = 1234.5f;
  r.y.suffix_density = 0.0421f;
  r.y.light_index = 31u;
  r.ucw = 3.25e-5f;
  r.confidence = 20.0f;
  r.p_hat = 1.5e7f;
  return r;
}

TEST(RestirReservoir, PackedRoundTrip) {
  Rng rng = rng_init(3, 1, 4, 1);
  for (int i = 0; i < 1000; ++i) {
    Reservoir r = sample_reservoir(rng);
    Reservoir u = unpack_reservoir(pack_reservoir(r));
    EXPECT_EQ(u.y.x1.instance, r.y.x1.instance);
    EXPECT_EQ(u.y.x1.geometry, r.y.x1.geometry);
    EXPECT_EQ(u.y.x1.triangle, r.y.x1.triangle);
    EXPECT_EQ(u.y.x1.bary, r.y.x1.bary);
    EXPECT_EQ(u.y.x1.lod, r.y.x1.lod);
    EXPECT_EQ(u.y.xk.instance, r.y.xk.instance);
    EXPECT_EQ(u.y.xk.geometry, r.y.xk.geometry);
    EXPECT_EQ(u.y.xk.triangle, r.y.xk.triangle);
    EXPECT_EQ(u.y.xk.bary, r.y.xk.bary);
    EXPECT_EQ(u.y.xk.lod, r.y.xk.lod);
    EXPECT_EQ(u.y.xk_radiance, r.y.xk_radiance);
    // Octahedral snorm16: worst-case angular error ~ 2 / 32767 across the diamond, a few 1e-5 rad.
    EXPECT_GT(dot(u.y.xk_direction, r.y.xk_direction), 1.0f - 1e-8f * 2e2f);
    EXPECT_EQ(u.y.k, r.y.k);
    EXPECT_EQ(u.y.segments, r.y.segments);
    EXPECT_EQ(u.y.flags, r.y.flags);
    EXPECT_EQ(u.y.seed, r.y.seed);
    EXPECT_NEAR(u.y.lens.x, 0.25f, 1.0f / 65535.0f);
    EXPECT_NEAR(u.y.lens.y, 0.75f, 1.0f / 65535.0f);
    EXPECT_FLOAT_EQ(u.y.time, 0.5f);
    EXPECT_EQ(u.y.jitter.x, r.y.jitter.x);
    EXPECT_EQ(u.y.jitter.y, r.y.jitter.y);
    EXPECT_EQ(u.y.density, r.y.density);
    EXPECT_EQ(u.y.light_pdf_end, r.y.light_pdf_end);
    EXPECT_EQ(u.y.suffix_density, r.y.suffix_density);
    EXPECT_EQ(u.y.light_index, r.y.light_index);
    EXPECT_EQ(u.ucw, r.ucw);
    EXPECT_EQ(u.p_hat, r.p_hat);
    EXPECT_FLOAT_EQ(u.confidence, 20.0f);
  }
}

TEST(RestirReservoir, NoSurfaceStaysNone) {
  Rng rng = rng_init(1, 2, 3, 4);
  Reservoir r = sample_reservoir(rng);
  r.y.xk = surface_none();
  r.y.flags = SAMPLE_VALID | SAMPLE_ESCAPED;
  Reservoir u = unpack_reservoir(pack_reservoir(r));
  EXPECT_EQ(u.y.xk.instance, SURFACE_NONE);
  EXPECT_EQ(u.y.flags, SAMPLE_VALID | SAMPLE_ESCAPED);
}

TEST(RestirReservoir, OctahedralMapCoversTheSphere) {
  for (vec3 d : {vec3(0, 0, 1), vec3(0, 0, -1), vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0),
                 normalize(vec3(-1, -1, -1)), normalize(vec3(1, -2, -0.1f))}) {
    vec3 e = octahedral_decode(octahedral_encode(d));
    EXPECT_NEAR(e.x, d.x, 1e-6f);
    EXPECT_NEAR(e.y, d.y, 1e-6f);
    EXPECT_NEAR(e.z, d.z, 1e-6f);
  }
}

}  // namespace
}  // namespace strata::gpu
