#pragma once
// The ReSTIR options of a session as command-line flags (strata stream, strata eval): each is sent
// only when given, so that the server's defaults apply otherwise (RenderOptions in render.proto).
#include <cstdint>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "strata/v1/render.pb.h"

namespace strata::client {

struct RestirFlags {
  std::string shift, mis, suffix, layer_mode, lod_mapping, lod_vertices;  // empty: not given
  std::optional<bool> lod_matching, deep_backup;
  std::optional<float> confidence_cap, still_confidence_cap, spatial_radius, colour_cv;
  std::optional<uint32_t> spatial_neighbors, initial_candidates, light_candidates, disocclusion_spatial_neighbors, disocclusion_initial_candidates, direct_strata,
      albedo_strata, layers, hole_fill_radius, silhouette_band, reveal_lookahead;
  bool no_temporal = false, no_spatial = false, biased = false, no_temporal_filter = false;
};

// Adds --shift, --mis, --suffix, --confidence-cap, --still-confidence-cap, --spatial-neighbors, --spatial-radius,
// --initial-candidates, --light-candidates, --disocclusion-spatial-neighbors, --direct-strata,
// --albedo-strata, --colour-cv, --layers, --hole-fill-radius, --silhouette-band, --deep-backup, --layer-mode, --lod-mapping, --lod-matching, --lod-vertices, --no-temporal, --no-spatial, --no-temporal-filter and --biased to `cmd`.
void add_restir_flags(CLI::App* cmd, RestirFlags& r);

// The given flags as they are written on a command line ("" when none is given).
std::string restir_flags_text(const RestirFlags& r);

// Sets the given flags in `o`; throws std::runtime_error naming a flag whose value is not allowed.
void set_restir_options(const RestirFlags& r, strata::v1::RenderOptions& o);

}  // namespace strata::client
