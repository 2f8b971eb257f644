// `strata stream|eval --camera-path FILE.json`: any bytes must give frames or a
// std::runtime_error naming the file and the entry (the client prints it and exits 1).
#include <stdexcept>

#include "camera_path.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static strata::fuzz::MemoryFile file;
  file.write(data, size);
  strata::fuzz::expect_clean("camera_path", [&] {
    try {
      (void)strata::client::load_camera_path(file.path());
    } catch (const std::runtime_error&) {
      // the client's own error, with the file and entry
    }
  });
  return 0;
}
