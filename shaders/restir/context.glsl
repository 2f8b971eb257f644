// The context of the ReSTIR library: everything the files under shaders/restir read that is
// neither the scene (the scene bridge, include/scene_bridge.glsl, is their only access to
// geometry, materials, lights and rays) nor an argument. It is a set of functions declared here and
// implemented by the bindings every ReSTIR pass shares (restir/restir_pass.glsl), so the library
// never names a uniform block or a buffer of the passes:
//   the frame: image sizes, random streams, history flags, how domains fix their primary vertex,
//     the shutter's time partitions (GpuFrameConstants, include/frame_data.h);
//   the method's constants (GpuRestirConstants, restir/restir_data.h);
//   the statistics counters (COUNTER_*, restir/restir_data.h);
//   domain indexing (restir/domain.h) in the current and the previous frame.
#ifndef STRATA_RESTIR_CONTEXT_GLSL
#define STRATA_RESTIR_CONTEXT_GLSL

#include "sampling/rng.h"

// The frame.
uvec2 image_size(bool prev);                 // pixels of the current (prev = false) or previous frame
Rng frame_rng(uint key, uint salt);          // rng_init(key, salt) of this frame and seed (restir/rng_streams.h)
uint frame_key(uint key, uint stream);       // rng_key(key, stream) of this frame and seed
uint history_flags();                        // HISTORY_* (include/frame_data.h)
uint primary_mode();                         // PRIMARY_DOMAIN or PRIMARY_CENTRE (docs/ARCHITECTURE.md, "Domains and their primary vertex")
uint time_partitions();                      // K of RS-main Eq. 19 (render/frame_constants.h)

// The method's constants.
uint restir_layers();                        // k pixel layers (1 but for restir-multilayer)
uint restir_max_segments();                  // path length limit
uint restir_light_candidates();              // NEE light samples per vertex
uint restir_shift_mode();                    // SHIFT_HYBRID or SHIFT_RECONNECTION
uint restir_suffix_mode();                   // SUFFIX_*
float restir_spatial_radius();               // pixels
float confidence_cap_of(GpuPrimaryHit e);    // RS-main 3.4 for the domain whose primary vertex is e

// The material of visibility-buffer entry `entry` of the current (prev = false) or previous frame,
// whose surface is `s` (primary_surface_hit): a fixed primary vertex's, at its primary footprint.
SurfaceMaterial fixed_primary_material(bool prev, uint entry, SurfaceHit s);

// The statistics: adds n to counter COUNTER_*, or raises it to n.
void counter_add(uint counter, uint n);
void counter_max(uint counter, uint n);

// Domains: the index of (pixel, layer), their count, and the inverse, in either frame.
uint pixel_index(uvec2 p);
bool in_image(ivec2 p);
uint domain_of(uvec2 pixel, uint layer);
uint prev_domain_of(uvec2 pixel, uint layer);
uint domain_count();
uint prev_domain_count();
uvec2 domain_pixel_of(uint d);
uint domain_layer_of(uint d);
uvec2 prev_domain_pixel_of(uint d);
uint prev_domain_layer_of(uint d);

#endif
