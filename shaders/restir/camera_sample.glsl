// The camera sample of a path: subpixel position (box filter), lens sample and shutter time, the
// first random-number dimensions of its key (sampling/rng.h). The initial pass draws one per
// candidate path; with PRIMARY_DOMAIN the primary pass draws the pixel's sample of the frame (the
// key of candidate 0) and every path of the pixel's domain starts from its hit.
#ifndef STRATA_CAMERA_SAMPLE_GLSL
#define STRATA_CAMERA_SAMPLE_GLSL

#include "restir/primary_data.h"
#include "sampling/rng.h"

// Random-number dimensions of the camera sample; a path's vertex blocks follow (path_vertex.glsl).
const uint DIM_JITTER = 0u;  // 2 dimensions
const uint DIM_LENS = 2u;    // 2 dimensions
const uint DIM_TIME = 4u;    // shutter time (RS-main 4.4)

struct CameraSample {
  vec2 jitter;
  vec2 lens;  // on the unorm16 grid a path sample stores it on (restir/reservoir.h)
  float time;
};

CameraSample camera_sample(uint key) {
  CameraSample c;
  c.jitter = vec2(rng_dim(key, DIM_JITTER), rng_dim(key, DIM_JITTER + 1u));
  c.lens = unpackUnorm2x16(packUnorm2x16(vec2(rng_dim(key, DIM_LENS), rng_dim(key, DIM_LENS + 1u))));
  // Always part of the sample so that shifts between frames with and without motion blur stay
  // bijections; the camera depends on it only over an open shutter.
  c.time = rng_dim(key, DIM_TIME);
  return c;
}

// The camera sample a visibility-buffer entry was traced with.
CameraSample primary_camera_sample(GpuPrimaryHit p) {
  CameraSample c;
  c.jitter = p.jitter;
  c.lens = unpackUnorm2x16(p.lens);
  c.time = p.time;
  return c;
}

#endif
