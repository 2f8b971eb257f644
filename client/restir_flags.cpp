#include "restir_flags.h"

#include <stdexcept>

namespace strata::client {

void add_restir_flags(CLI::App* cmd, RestirFlags& r) {
  cmd->add_option("--shift", r.shift, "ReSTIR shift mapping: reconnection | hybrid (default: the server's, hybrid)")
      ->check(CLI::IsMember({"reconnection", "hybrid"}));
  cmd->add_option("--mis", r.mis, "ReSTIR spatial MIS weights: balance | pairwise (default: the server's, pairwise)")
      ->check(CLI::IsMember({"balance", "pairwise"}));
  cmd->add_option("--suffix", r.suffix,
                  "ReSTIR path suffixes when the scene changed: auto | replay | cached (biased) | fail (default: the server's, auto)")
      ->check(CLI::IsMember({"auto", "replay", "cached", "fail"}));
  cmd->add_option("--confidence-cap", r.confidence_cap, "ReSTIR confidence cap of the temporal history where something moved (1..1000; default the method's: 2; restir-di 4)");
  cmd->add_option("--still-confidence-cap", r.still_confidence_cap,
                  "ReSTIR: confidence cap where nothing moved, the camera and every instance (1..1000; 0: --confidence-cap; default 8)");
  cmd->add_option("--spatial-neighbors", r.spatial_neighbors, "ReSTIR spatial neighbours per pixel (0..8; default 2)");
  cmd->add_option("--spatial-radius", r.spatial_radius, "ReSTIR spatial radius in pixels (1..256; default 2.5% of the image height, at least 4)");
  cmd->add_option("--initial-candidates", r.initial_candidates, "ReSTIR candidate paths per pixel (1..64; default 1)");
  cmd->add_option("--light-candidates", r.light_candidates, "ReSTIR NEE samples per path vertex (1..32; default 1)");
  cmd->add_option("--disocclusion-spatial-neighbors", r.disocclusion_spatial_neighbors,
                  "ReSTIR spatial neighbours of pixels without history (0..8; 0: --spatial-neighbors; default 6)");
  cmd->add_option("--disocclusion-initial-candidates", r.disocclusion_initial_candidates,
                  "ReSTIR splat: candidate paths of pixels no splat reached, restir-multilayer: of disoccluded ones (0..64; 0: the "
                  "method's, 8 for restir-multilayer, else --initial-candidates; = --initial-candidates: off; default 0)");
  cmd->add_option("--direct-strata", r.direct_strata,
                  "ReSTIR: G x G stratified camera samples for what pixels at edges of directly seen emission see (1..8; default 3)");
  cmd->add_option("--albedo-strata", r.albedo_strata,
                  "ReSTIR gather: G x G camera samples of the albedo control variate at albedo edges (1..8; 1: off; default 2)");
  cmd->add_option("--colour-cv", r.colour_cv,
                  "ReSTIR gather and splat: largest b of the colour control variate, the share of the way from each pixel's colour to that "
                  "of its initial paths, less where their colours spread (0..1; 0: off; default 0.6)");
  cmd->add_option("--layers", r.layers,
                  "restir-multilayer: pixel layers (0..8; 0: auto, measured from the scene's depth complexity; default 0)");
  cmd->add_option("--hole-fill-radius", r.hole_fill_radius, "restir-multilayer: hole filling radius in pixels (0..8; 0: off; default 3)");
  cmd->add_option("--silhouette-band", r.silhouette_band,
                  "restir-multilayer: deep domains farther than this many pixels from a front-layer silhouette are dormant, "
                  "tracked but not sampled (0..32; 0: off; default 1)");
  cmd->add_option("--reveal-lookahead", r.reveal_lookahead,
                  "restir-multilayer: deep domains whose motion is known sample when predicted to be uncovered within this many "
                  "frames, else they are dormant (0..16; 0: off; default 4)");
  cmd->add_option("--deep-backup", r.deep_backup,
                  "restir-multilayer: a disoccluded pixel takes the previous deep domain that held its hit as a backup sample "
                  "(RS-main 4.2 across layers; true | false; default true)");
  cmd->add_option("--layer-mode", r.layer_mode,
                  "restir-multilayer: active | uniform | no-depth-ranges (the ML paper's validation variants; default active)")
      ->check(CLI::IsMember({"active", "uniform", "no-depth-ranges"}));
  cmd->add_option("--lod-mapping", r.lod_mapping, "ReSTIR: auto | off | uv (LoD-aware reuse, the LOD paper's vertex mapping; default auto)")
      ->check(CLI::IsMember({"auto", "off", "uv"}));
  cmd->add_option("--lod-matching", r.lod_matching,
                  "ReSTIR, --lod-mapping uv: match UVs that several points share (LOD Alg. 1; true | false; default true)");
  cmd->add_option("--lod-vertices", r.lod_vertices, "ReSTIR, --lod-mapping uv: both | primary | reconnection (LOD Fig. 5; default both)")
      ->check(CLI::IsMember({"both", "primary", "reconnection"}));
  cmd->add_flag("--no-temporal", r.no_temporal, "ReSTIR: no temporal reuse");
  cmd->add_flag("--no-temporal-filter", r.no_temporal_filter, "ReSTIR gather: take history from any previous pixel (no surface test)");
  cmd->add_flag("--no-spatial", r.no_spatial, "ReSTIR: no spatial reuse");
  cmd->add_flag("--biased", r.biased, "ReSTIR: confidence-only temporal weights, as in the DI tutorial (biased)");
}

std::string restir_flags_text(const RestirFlags& r) {
  std::string s;
  auto add = [&](const std::string& flag, const std::string& value) { s += (s.empty() ? "" : " ") + flag + (value.empty() ? "" : " " + value); };
  auto num = [](double v) {
    std::string t = std::to_string(v);
    t.erase(t.find_last_not_of('0') + 1);
    if (!t.empty() && t.back() == '.') t.pop_back();
    return t;
  };
  if (!r.shift.empty()) add("--shift", r.shift);
  if (!r.mis.empty()) add("--mis", r.mis);
  if (!r.suffix.empty()) add("--suffix", r.suffix);
  if (r.confidence_cap) add("--confidence-cap", num(*r.confidence_cap));
  if (r.still_confidence_cap) add("--still-confidence-cap", num(*r.still_confidence_cap));
  if (r.spatial_neighbors) add("--spatial-neighbors", std::to_string(*r.spatial_neighbors));
  if (r.spatial_radius) add("--spatial-radius", num(*r.spatial_radius));
  if (r.initial_candidates) add("--initial-candidates", std::to_string(*r.initial_candidates));
  if (r.light_candidates) add("--light-candidates", std::to_string(*r.light_candidates));
  if (r.disocclusion_spatial_neighbors) add("--disocclusion-spatial-neighbors", std::to_string(*r.disocclusion_spatial_neighbors));
  if (r.disocclusion_initial_candidates)
    add("--disocclusion-initial-candidates", std::to_string(*r.disocclusion_initial_candidates));
  if (r.direct_strata) add("--direct-strata", std::to_string(*r.direct_strata));
  if (r.albedo_strata) add("--albedo-strata", std::to_string(*r.albedo_strata));
  if (r.colour_cv) add("--colour-cv", num(*r.colour_cv));
  if (r.layers) add("--layers", std::to_string(*r.layers));
  if (r.hole_fill_radius) add("--hole-fill-radius", std::to_string(*r.hole_fill_radius));
  if (r.silhouette_band) add("--silhouette-band", std::to_string(*r.silhouette_band));
  if (r.reveal_lookahead) add("--reveal-lookahead", std::to_string(*r.reveal_lookahead));
  if (r.deep_backup) add("--deep-backup", *r.deep_backup ? "true" : "false");
  if (!r.layer_mode.empty()) add("--layer-mode", r.layer_mode);
  if (!r.lod_mapping.empty()) add("--lod-mapping", r.lod_mapping);
  if (r.lod_matching) add("--lod-matching", *r.lod_matching ? "true" : "false");
  if (!r.lod_vertices.empty()) add("--lod-vertices", r.lod_vertices);
  if (r.no_temporal) add("--no-temporal", "");
  if (r.no_temporal_filter) add("--no-temporal-filter", "");
  if (r.no_spatial) add("--no-spatial", "");
  if (r.biased) add("--biased", "");
  return s;
}

void set_restir_options(const RestirFlags& r, v1::RenderOptions& o) {
  if (r.shift == "reconnection") o.set_shift(v1::SHIFT_RECONNECTION);
  else if (r.shift == "hybrid") o.set_shift(v1::SHIFT_HYBRID);
  else if (!r.shift.empty()) throw std::runtime_error("--shift: '" + r.shift + "' is not one of reconnection, hybrid");
  if (r.mis == "balance") o.set_mis(v1::MIS_BALANCE);
  else if (r.mis == "pairwise") o.set_mis(v1::MIS_PAIRWISE);
  else if (!r.mis.empty()) throw std::runtime_error("--mis: '" + r.mis + "' is not one of balance, pairwise");
  if (r.suffix == "auto") o.set_suffix(v1::SUFFIX_AUTO);
  else if (r.suffix == "replay") o.set_suffix(v1::SUFFIX_REPLAY);
  else if (r.suffix == "cached") o.set_suffix(v1::SUFFIX_CACHED);
  else if (r.suffix == "fail") o.set_suffix(v1::SUFFIX_FAIL);
  else if (!r.suffix.empty()) throw std::runtime_error("--suffix: '" + r.suffix + "' is not one of auto, replay, cached, fail");
  if (r.confidence_cap) o.set_confidence_cap(*r.confidence_cap);
  if (r.still_confidence_cap) o.set_still_confidence_cap(*r.still_confidence_cap);
  if (r.spatial_neighbors) o.set_spatial_neighbors(*r.spatial_neighbors);
  if (r.spatial_radius) o.set_spatial_radius(*r.spatial_radius);
  if (r.initial_candidates) o.set_initial_candidates(*r.initial_candidates);
  if (r.light_candidates) o.set_light_candidates(*r.light_candidates);
  if (r.disocclusion_spatial_neighbors) o.set_disocclusion_spatial_neighbors(*r.disocclusion_spatial_neighbors);
  if (r.disocclusion_initial_candidates) o.set_disocclusion_initial_candidates(*r.disocclusion_initial_candidates);
  if (r.direct_strata) o.set_direct_strata(*r.direct_strata);
  if (r.albedo_strata) o.set_albedo_strata(*r.albedo_strata);
  if (r.colour_cv) o.set_colour_cv(*r.colour_cv);
  if (r.layers) o.set_layers(*r.layers);
  if (r.hole_fill_radius) o.set_hole_fill_radius(*r.hole_fill_radius);
  if (r.silhouette_band) o.set_silhouette_band(*r.silhouette_band);
  if (r.reveal_lookahead) o.set_reveal_lookahead(*r.reveal_lookahead);
  if (r.deep_backup) o.set_deep_backup(*r.deep_backup);
  if (r.layer_mode == "active") o.set_layer_mode(v1::LAYER_MODE_ACTIVE);
  else if (r.layer_mode == "uniform") o.set_layer_mode(v1::LAYER_MODE_UNIFORM);
  else if (r.layer_mode == "no-depth-ranges") o.set_layer_mode(v1::LAYER_MODE_NO_DEPTH_RANGES);
  else if (!r.layer_mode.empty())
    throw std::runtime_error("--layer-mode: '" + r.layer_mode + "' is not one of active, uniform, no-depth-ranges");
  if (r.lod_mapping == "auto") o.set_lod_mapping(v1::LOD_MAPPING_AUTO);
  else if (r.lod_mapping == "off") o.set_lod_mapping(v1::LOD_MAPPING_OFF);
  else if (r.lod_mapping == "uv") o.set_lod_mapping(v1::LOD_MAPPING_UV);
  else if (!r.lod_mapping.empty()) throw std::runtime_error("--lod-mapping: '" + r.lod_mapping + "' is not one of auto, off, uv");
  if (r.lod_matching) o.set_lod_matching(*r.lod_matching);
  if (r.lod_vertices == "both") o.set_lod_vertices(v1::LOD_VERTICES_BOTH);
  else if (r.lod_vertices == "primary") o.set_lod_vertices(v1::LOD_VERTICES_PRIMARY);
  else if (r.lod_vertices == "reconnection") o.set_lod_vertices(v1::LOD_VERTICES_RECONNECTION);
  else if (!r.lod_vertices.empty())
    throw std::runtime_error("--lod-vertices: '" + r.lod_vertices + "' is not one of both, primary, reconnection");
  if (r.no_temporal) o.set_temporal_reuse(false);
  if (r.no_temporal_filter) o.set_temporal_filter(false);
  if (r.no_spatial) o.set_spatial_reuse(false);
  if (r.biased) o.set_unbiased(false);
}

}  // namespace strata::client
