// FrameInput as it arrives on a stream: parse, then parse_frame_input against a real scene (the
// built-in carousel: instances with LoD levels), then merged into a pending input the way inputs
// that arrive during a frame are. Must end in a pending input or an INVALID_ARGUMENT naming the field.
#include "fuzz_support.h"
#include "scene/scene_io.h"
#include "service/frame_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const strata::scene::Scene scene = strata::scene::builtin_scene("lod-cliff");
  strata::v1::FrameInput in;
  if (!in.ParseFromArray(data, int(size))) return 0;
  strata::service::ServiceLimits limits;
  strata::fuzz::expect_clean("frame_input", [&] {
    auto first = strata::service::parse_frame_input(in, scene, limits);
    auto second = strata::service::parse_frame_input(in, scene, limits);
    first.merge_newer(std::move(second));
  });
  return 0;
}
