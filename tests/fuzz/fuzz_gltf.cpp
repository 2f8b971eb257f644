// glTF loading: bytes that start like a .glb go through scene::load_glb_bytes (what an inline
// SceneSource.glb meets), the rest through scene::load_gltf_file as a .gltf document (what
// --scene-dir files and `stratad render --scene FILE` meet). Both must end in a scene or a
// SceneError naming the problem.
#include <span>

#include "fuzz_support.h"
#include "scene/scene_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // Small limits keep each input fast; they are the same checks with smaller numbers.
  strata::scene::LoadLimits limits;
  limits.max_file_bytes = 1 << 20;
  limits.max_triangles = 100'000;
  limits.max_instances = 256;
  static strata::fuzz::MemoryFile file;
  strata::fuzz::expect_clean("gltf", [&] {
    if (size >= 4 && data[0] == 'g' && data[1] == 'l' && data[2] == 'T' && data[3] == 'F') {
      (void)strata::scene::load_glb_bytes(std::span<const uint8_t>(data, size), "fuzz.glb", limits);
    } else {
      file.write(data, size);
      (void)strata::scene::load_gltf_file(file.path(), limits);
    }
  });
  return 0;
}
