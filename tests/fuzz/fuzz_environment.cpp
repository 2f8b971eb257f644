// Environment maps: any bytes must give an EnvironmentMap with its sampling tables (Radiance .hdr or
// OpenEXR) or a SceneError naming the problem (not an HDR image, undecodable, over the limit, a
// texel that is not a finite non-negative radiance).
#include <span>

#include "fuzz_support.h"
#include "scene/environment_map.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  strata::fuzz::expect_clean("environment", [&] {
    strata::scene::EnvironmentOptions options;
    options.max_dimension = 1024;  // the same check with a smaller number keeps each input fast
    const strata::scene::EnvironmentMap map =
        strata::scene::decode_environment_map(std::span<const uint8_t>(data, size), "fuzz.hdr", options);
    (void)strata::scene::sample_environment(map, {0.5f, 0.5f});
  });
  return 0;
}
