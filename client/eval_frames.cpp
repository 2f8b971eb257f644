#include "eval_frames.h"

#include <sstream>
#include <stdexcept>
#include <string>

#include "camera_path.h"

namespace strata::client {
namespace {

std::string number(float v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// Every entry sets animation_frame and only the parts of a frame state: the methods' settings
// come from eval's own options, so that every method sees the same frames.
void check_entry(const v1::FrameInput& in, const std::string& at) {
  if (!in.has_animation_frame())
    throw std::runtime_error(at + " has no animation_frame: every entry of an eval camera path sets it (the scene's "
                                  "transforms and LoD levels at that frame; camera, transforms and lod_changes may replace them)");
  std::string extra;
  if (in.has_options()) extra = "options";
  else if (in.has_resolution()) extra = "resolution";
  else if (in.encodings_size() > 0) extra = "encodings";
  if (!extra.empty())
    throw std::runtime_error(at + " sets " + extra + ": an eval camera path sets only animation_frame, camera, transforms and "
                                  "lod_changes (the methods' settings are eval's options)");
}

}  // namespace

void prepare_eval_frames(EvalSettings& s, bool frames_given) {
  if (s.shutter && !(*s.shutter >= 0.0f && *s.shutter <= 1.0f))
    throw std::runtime_error("--shutter = " + number(*s.shutter) + " is outside [0, 1] (fraction of the frame interval)");
  const bool open = s.shutter && *s.shutter > 0.0f;
  if (s.camera_path.empty()) {
    if (open)
      throw std::runtime_error("--shutter = " + number(*s.shutter) + " needs --camera-path whose entries all set camera: "
                               "the default animation's frames have no camera to carry a shutter");
    return;
  }
  if (frames_given)
    throw std::runtime_error("--frames cannot be given with --camera-path: the camera path's entries are the frames");
  s.path = load_camera_path(s.camera_path);
  for (size_t i = 0; i < s.path.size(); ++i) {
    const std::string at = s.camera_path + ": frames[" + std::to_string(i) + "]";
    check_entry(s.path[i], at);
    if (!s.shutter) continue;
    if (open && !s.path[i].has_camera())
      throw std::runtime_error("--shutter = " + number(*s.shutter) + " needs a camera in every entry of --camera-path: " + at +
                               " has none (without a camera there is no shutter to open)");
    if (s.path[i].has_camera()) s.path[i].mutable_camera()->set_shutter(*s.shutter);
  }
  s.frames = uint32_t(s.path.size());
}

v1::FrameInput eval_frame_input(const EvalSettings& s, uint32_t f) {
  if (!s.path.empty()) return s.path.at(f);
  v1::FrameInput in;
  in.set_animation_frame(f);
  return in;
}

v1::FrameState eval_frame_state(const EvalSettings& s, uint32_t f) {
  const v1::FrameInput in = eval_frame_input(s, f);
  v1::FrameState st;
  st.set_animation_frame(in.animation_frame());
  if (in.has_camera()) *st.mutable_camera() = in.camera();
  if (f == 0 && st.has_camera()) st.mutable_camera()->set_shutter(0.0f);
  *st.mutable_transforms() = in.transforms();
  *st.mutable_lod_changes() = in.lod_changes();
  return st;
}

}  // namespace strata::client
