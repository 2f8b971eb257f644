#pragma once
// The frames `strata eval` plays and references: a scene's default animation (animation_frame
// 0..frames-1), or a camera path (client/camera_path.h) whose entries each set animation_frame and
// may set camera, transforms and lod_changes. --shutter sets every entry's camera.shutter (motion
// blur, RS-main 4.4), so it needs a camera path whose entries all set a camera.
#include <cstdint>

#include "eval_runner.h"

namespace strata::client {

// Checks --camera-path, --shutter and --frames together and loads the path into `s.path`
// (`s.frames` becomes its length). Throws std::runtime_error naming the option or the entry.
void prepare_eval_frames(EvalSettings& s, bool frames_given);

// What the sessions receive for frame `f` (session and sequence left unset).
v1::FrameInput eval_frame_input(const EvalSettings& s, uint32_t f);

// The state a reference of frame `f` shows. A session's first frame has no frame before it, so
// its shutter cannot open: frame 0 is an instant (shutter 0) in its reference too.
v1::FrameState eval_frame_state(const EvalSettings& s, uint32_t f);

}  // namespace strata::client
