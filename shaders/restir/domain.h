// Domain addressing (docs/ARCHITECTURE.md, "Domains"): a ReSTIR domain is a (pixel, layer) pair
// (the ML paper's pixel-layer domains; layer 0 is the front layer; only restir-multilayer has more:
// restir/layer_data.h). Every
// buffer of per-domain data (reservoirs, contributions, splat keys) is indexed by domain_index and
// by nothing else, so adding layers changes this one function and the buffers' sizes.
#ifndef STRATA_DOMAIN_H
#define STRATA_DOMAIN_H
#include "include/lang.h"

STRATA_NAMESPACE_BEGIN

// Layer-major: all of layer 0's pixels row by row, then layer 1's, ...
INLINE uint domain_index(uvec2 pixel, uint layer, uint width, uint height) {
  return (layer * height + pixel.y) * width + pixel.x;
}

// The pixel of a layer-0 domain index (the inverse of domain_index for layer 0; for any layer, of the
// index modulo width * height).
INLINE uvec2 domain_pixel(uint index, uint width) { return uvec2(index % width, index / width); }

// The contribution buffer, per frame (sections of `domains` = pixels x layers or of `pixels`):
// f(Y) of each domain's reservoir, what each pixel's camera rays see directly, and each domain's
// estimate sum_i w_i f(Y_i) / p-hat(Y_i) over the candidates of the last pass that resampled it
// (restir/gris.h, gris_stream_path), which the shade pass adds to the image.
INLINE uint contribution_emission_index(uint pixel, uint domains) { return domains + pixel; }
INLINE uint contribution_estimate_index(uint domain, uint domains, uint pixels) { return domains + pixels + domain; }
// Then per pixel the albedo control variate's terms (restir_initial.comp, restir_shade.comp): the mean
// albedo of the pixel's stratified camera samples minus the domain primary vertex's (w: 1 where taken),
// that vertex's albedo, and the pixel's demodulated radiance kept from frame to frame (w: frames).
INLINE uint contribution_cv_delta_index(uint pixel, uint domains, uint pixels) { return 2u * domains + pixels + pixel; }
INLINE uint contribution_cv_albedo_index(uint pixel, uint domains, uint pixels) { return 2u * domains + 2u * pixels + pixel; }
INLINE uint contribution_cv_history_index(uint pixel, uint domains, uint pixels) { return 2u * domains + 3u * pixels + pixel; }
// With the colour control variate (restir_shade.comp), per pixel: the initial pass's estimate of the
// reflected light (rgb) and, in w's bits, the window pixels whose reservoirs the spatial pass reused
// (colour_cv_window_bit).
INLINE uint contribution_canonical_index(uint pixel, uint domains, uint pixels) { return 2u * domains + 4u * pixels + pixel; }

// The colour control variate's window: the pixels within COLOUR_CV_RADIUS of a pixel (Chebyshev),
// one bit each, row by row; the centre's bit is never set.
CONST_DEF int COLOUR_CV_RADIUS = 2;
INLINE uint colour_cv_window_bit(ivec2 offset) {
  return uint((offset.y + COLOUR_CV_RADIUS) * (2 * COLOUR_CV_RADIUS + 1) + offset.x + COLOUR_CV_RADIUS);
}

STRATA_NAMESPACE_END
#endif
