#version 460
// Pass `shade` (stage shade): each pixel's estimate from the last pass that resampled it, the
// conditional expectation of f(Y) W_Y (GRIS, RS-main Eq. 5) over that pass's candidates
// (restir/gris.h, gris_stream_path), plus the initial pass's estimate of what the camera rays see directly
// (paths of one segment, which are not resampled: restir_initial.comp), and for the gather methods the
// albedo control variate of pixels at albedo edges (docs/ARCHITECTURE.md, "The albedo control
// variate"), added to the accumulation buffer as one sample.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "include/bindings.h"
#include "include/frame_data.h"
#include "material/bsdf.h"
#include "restir/domain.h"
#include "restir/colour_cv.h"
#include "restir/layer_data.h"
#include "restir/restir_data.h"

const float CV_HISTORY_FRAMES = 8.0;

layout(set = 0, binding = BINDING_FRAME, std140) uniform Frame { GpuFrameConstants u_frame; };
layout(set = 0, binding = BINDING_COUNTERS, std430) buffer Counters { uint b_counters[]; };
layout(set = 0, binding = BINDING_CONTRIBUTION, std430) buffer Contribution { vec4 b_contribution[]; };
layout(set = 0, binding = BINDING_RESTIR, std140) uniform Restir { GpuRestirConstants u_restir; };
layout(set = 0, binding = BINDING_ACCUM, std430) buffer Accum { vec4 b_accum[]; };
layout(set = 0, binding = BINDING_DOMAINS, std430) readonly buffer Domains { GpuDomainRange b_domains[]; };

uint pixel_index(uvec2 pixel) { return pixel.y * u_frame.width + pixel.x; }

// The colour control variate (docs/ARCHITECTURE.md, "The colour control variate"): with A the
// pixel's estimate (reflected light, after temporal and spatial reuse) and B the initial pass's
// estimate of the same frame,
//   E = A + b (I - w lum^T) (B - A),   lum(w) = 1,
// keeps A's luminance (lum^T (I - w lum^T) = 0) and moves its colour towards B's, whose paths are
// all of this frame's NEE connections and emitter hits, where A's are mostly the one path its history
// holds. E[B - A] = 0 (both estimate the pixel: given its primary vertex for the gather methods, its
// integral for the splat methods, whose samples carry their camera samples), so E is unbiased for any
// b and w independent of A and B: both come from the initial estimates B_j of the pixels in a
// window around this one, leaving out this pixel and those whose reservoirs the spatial pass reused
// here (their initial paths are in A). w is the colour of their sum; b shrinks from colour_cv where
// the B_j disagree in colour (restir/colour_cv.h). Returns E, or A where the window sees no light.
vec3 colour_control_variate(uvec2 pixel, vec3 a, uint pixels, uint domains) {
  vec4 own = b_contribution[contribution_canonical_index(pixel_index(pixel), domains, pixels)];
  uint reused = floatBitsToUint(own.w);
  ColourWindow window = colour_window_empty();
  for (int dy = -COLOUR_CV_RADIUS; dy <= COLOUR_CV_RADIUS; ++dy) {
    for (int dx = -COLOUR_CV_RADIUS; dx <= COLOUR_CV_RADIUS; ++dx) {
      ivec2 d = ivec2(dx, dy);
      ivec2 q = ivec2(pixel) + d;
      if (d == ivec2(0) || (reused & (1u << colour_cv_window_bit(d))) != 0u) continue;
      if (q.x < 0 || q.y < 0 || q.x >= int(u_frame.width) || q.y >= int(u_frame.height)) continue;
      colour_window_add(window, b_contribution[contribution_canonical_index(pixel_index(uvec2(q)), domains, pixels)].rgb);
    }
  }
  float y = luminance(window.sum);
  if (!(y > 0.0) || isinf(y)) return a;
  vec3 w = window.sum / y;
  float b = colour_cv_b(u_restir.colour_cv, u_restir.colour_cv_spread, colour_window_spread(window, w, y));
  vec3 d = own.rgb - a;
  vec3 e = a + b * (d - w * luminance(d));
  return any(isnan(e)) || any(isinf(e)) ? a : e;
}

// view_layer i >= 1: the estimate of the pixel's layer-i domain, I_i of ML Eq. 3 (its surface's
// radiance towards the camera with the camera's visibility left out), 0 where the domain is inactive.
vec3 layer_view(uvec2 pixel, uint pixels, uint domains) {
  uint domain = domain_index(pixel, u_restir.view_layer, u_frame.width, u_frame.height);
  if ((b_domains[domain].flags & DOMAIN_ACTIVE) == 0u) return vec3(0.0);
  return b_contribution[contribution_estimate_index(domain, domains, pixels)].rgb;
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= u_frame.width || pixel.y >= u_frame.height) return;
  uint index = pixel_index(pixel);
  uint domain = domain_index(pixel, 0u, u_frame.width, u_frame.height);  // the front layer is the image
  uint pixels = u_frame.width * u_frame.height;
  uint domains = pixels * u_restir.layers;
  if (u_restir.view_layer > 0u) {
    vec3 l = layer_view(pixel, pixels, domains);
    if (any(isnan(l)) || any(isinf(l)) || any(lessThan(l, vec3(0.0)))) {
      atomicAdd(b_counters[COUNTER_NONFINITE_REJECTED], 1u);
      l = vec3(0.0);
    }
    b_accum[index] += vec4(l, 1.0);
    return;
  }
  vec3 reflected = b_contribution[contribution_estimate_index(domain, domains, pixels)].rgb;
  vec3 l = reflected + b_contribution[contribution_emission_index(index, domains)].rgb;
  // A non-finite or negative estimate never reaches a pixel; it is counted. (The albedo control
  // variate below may then take a pixel slightly below 0: docs/ARCHITECTURE.md.)
  if (any(isnan(l)) || any(isinf(l)) || any(lessThan(l, vec3(0.0)))) {
    atomicAdd(b_counters[COUNTER_NONFINITE_REJECTED], 1u);
    l = vec3(0.0);
    reflected = vec3(0.0);
  } else if (u_restir.colour_cv > 0.0) {
    // After the test: E may take a channel slightly below 0, as the albedo control variate may
    // (docs/ARCHITECTURE.md); a non-finite E leaves A.
    vec3 e = colour_control_variate(pixel, reflected, pixels, domains);
    l += e - reflected;
    reflected = e;
  }
  if (u_restir.albedo_strata > 0u) {
    // The albedo control variate (docs/ARCHITECTURE.md): E_hat (A_mean - A(x_1)), with E_hat the
    // pixel's demodulated radiance of earlier frames, independent of this frame's camera samples.
    uint hi = contribution_cv_history_index(index, domains, pixels);
    vec4 history = (u_frame.history_flags & HISTORY_VALID) != 0u ? b_contribution[hi] : vec4(0.0);
    if (!(history.w > 0.0) || any(isnan(history)) || any(isinf(history))) history = vec4(0.0);
    vec4 delta = b_contribution[contribution_cv_delta_index(index, domains, pixels)];
    if (delta.w > 0.0) l += history.rgb * delta.rgb;
    vec3 a1 = b_contribution[contribution_cv_albedo_index(index, domains, pixels)].rgb;
    // This frame's demodulated radiance, where the primary vertex has an albedo to divide by.
    if (all(greaterThan(a1, vec3(1e-3)))) {
      float n = min(history.w + 1.0, CV_HISTORY_FRAMES);
      history = vec4(history.rgb + (reflected / a1 - history.rgb) / n, n);
    }
    b_contribution[hi] = history;
  }
  b_accum[index] += vec4(l, 1.0);
}
