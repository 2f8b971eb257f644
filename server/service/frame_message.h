#pragma once
// A rendered frame as the Frame message: images in the requested encodings, per-pass GPU time,
// the frame statistics of docs/ARCHITECTURE.md, Statistics, and what happened since the previous frame.
#include "render/frame_stats.h"
#include "service/session.h"
#include "strata/v1/render.pb.h"

namespace strata::service {

void fill_statistics(const render::FrameStats& stats, ::strata::v1::FrameStatistics* out);

// Encodes the images (on the calling thread) and fills every field.
::strata::v1::Frame make_frame_message(const RenderedFrame& frame);

}  // namespace strata::service
