// Session decisions: for the method (its method-table row), every option and the path tracer's
// features, what was requested, what the session uses, whether it applies, and why. Every row of the
// option table has a decision; one whose scope leaves out the method does not apply, with the table's
// reason (options::not_applying_reason), whatever the reasons below say.
#include <algorithm>
#include <optional>

#include "options/option_proto.h"
#include "render/light_sampler_choice.h"
#include "restir/domain.h"
#include "service/input_checks.h"
#include "service/options.h"

namespace strata::service {
namespace {

v1::Decision make(const std::string& name, const std::string& requested, const std::string& value, bool applies,
                  const std::string& reason) {
  v1::Decision d;
  d.set_name(name);
  d.set_requested(requested);
  d.set_value(value);
  d.set_applies(applies);
  d.set_reason(reason);
  return d;
}

std::string u(uint32_t v) { return std::to_string(v); }

// The session's layer count: 1 without pixel layers, else as requested or as `layers auto` measured
// it on the first frame; none while auto has not measured yet.
std::optional<uint32_t> layers_in_use(const render::MethodSpec& method, const v1::RenderOptions& eff,
                                      const std::optional<render::LayerCount>& measured) {
  if (!method.layers) return 1u;
  if (eff.layers() != 0) return eff.layers();
  if (measured) return measured->layers;
  return std::nullopt;
}

}  // namespace

std::vector<v1::Decision> decide(const render::MethodSpec& method, const std::string& requested_method,
                                 const v1::RenderOptions& req, const v1::RenderOptions& eff,
                                 const std::vector<v1::ImageEncoding>& encodings, const v1::SceneAnalysis& scene,
                                 const std::optional<render::LayerCount>& measured_layers) {
  std::vector<v1::Decision> out;
  const std::string m = method.name;
  const std::string no_reuse = "method " + m + " has no reuse; used by the restir-* methods";
  auto asked = [](bool has, const std::string& value) { return has ? value : std::string(); };
  // What the client asked for option `name`, as the table writes it; empty when not asked.
  auto asked_for = [&](const char* name) {
    const options::OptionSpec& row = *options::find_option(name);
    return options::has_value(req, row) ? options::value_text(row, options::get_value(req, row)) : std::string();
  };

  const bool di = method.direct_lighting;
  // `method auto` rewrites this decision with its choice and figures (service/method_auto.h).
  out.push_back(make("method", requested_method, m, true, method.summary));
  out.push_back(make("spp", asked(req.has_spp(), u(req.spp())), u(eff.spp()), true,
                     method.reuse ? "one reservoir per pixel, shaded once per frame (spp must be 1)" : "samples per pixel per frame"));
  out.push_back(make("max_depth", asked(req.has_max_depth(), u(req.max_depth())), u(eff.max_depth()), true,
                     di ? "path segments after the camera; restir-di uses at most 2 (camera, first hit, light)"
                        : "path segments after the camera"));

  // Resampling options. Each pass can be switched off; the options of a pass that is off do not apply.
  const bool temporal = method.reuse && eff.temporal_reuse();
  const bool spatial = method.reuse && eff.spatial_reuse() && eff.spatial_neighbors() > 0;
  auto on_off = [](bool b) { return std::string(b ? "on" : "off"); };
  const std::string no_temporal = "temporal reuse is off (temporal_reuse = false)";
  const std::string no_spatial = !eff.spatial_reuse() ? "spatial reuse is off (spatial_reuse = false)"
                                                      : "spatial reuse is off (spatial_neighbors = 0)";
  out.push_back(make("temporal_reuse", asked(req.has_temporal_reuse(), on_off(req.temporal_reuse())),
                     on_off(eff.temporal_reuse()), method.reuse,
                     method.reuse ? (eff.temporal_reuse() ? (method.splatting ? "the previous frame's reservoirs, splatted forward"
                                                                              : "the previous frame's reservoirs, by backprojection")
                                                          : "requested off: no temporal pass")
                                  : no_reuse));
  out.push_back(make("spatial_reuse", asked(req.has_spatial_reuse(), on_off(req.spatial_reuse())),
                     on_off(eff.spatial_reuse()), method.reuse,
                     method.reuse ? (eff.spatial_reuse() ? "the neighbours' reservoirs (spatial_neighbors within spatial_radius)"
                                                         : "requested off: no spatial pass")
                                  : no_reuse));
  out.push_back(make("shift", asked_for("shift"), option_text(eff, "shift"),
                     temporal || spatial,
                     !method.reuse ? no_reuse
                     : temporal || spatial ? "shift mapping between pixels' paths"
                                           : "temporal and spatial reuse are off: no shifts"));
  out.push_back(make("suffix", asked_for("suffix"), option_text(eff, "suffix"), temporal,
                     !method.reuse ? no_reuse
                     : !temporal   ? no_temporal
                     : eff.experimental().suffix() == v1::SUFFIX_CACHED
                         ? "a changed scene keeps each path's stored radiance after its reconnection vertex (biased)"
                     : eff.experimental().suffix() == v1::SUFFIX_FAIL
                         ? "a changed scene refuses temporal shifts of paths with a suffix (temporal.stale)"
                     : eff.experimental().suffix() == v1::SUFFIX_AUTO
                         ? "replay: a path's suffix is traced again in the other frame whenever an instance changed "
                           "(whether it met the changed instance is not known without tracing it); kept when nothing changed"
                         : "a path's suffix is traced again in the other frame whenever an instance changed"));
  out.push_back(make("mis", asked_for("mis"), option_text(eff, "mis"), spatial,
                     !method.reuse ? no_reuse : spatial ? "MIS weights of spatial resampling" : no_spatial));
  out.push_back(make("unbiased", asked(req.experimental().has_unbiased(), on_off(req.experimental().unbiased())), on_off(eff.experimental().unbiased()), temporal,
                     !method.reuse ? no_reuse
                     : !temporal   ? no_temporal
                     : eff.experimental().unbiased() ? "MIS weights for the temporal pair"
                                      : "confidence-only temporal weights, as in the ReSTIR DI tutorial (biased)"));
  out.push_back(make("confidence_cap", asked(req.has_confidence_cap(), format_float(req.confidence_cap())),
                     format_float(eff.confidence_cap()), temporal,
                     !method.reuse ? no_reuse
                     : !temporal   ? no_temporal
                     : req.has_confidence_cap()
                         ? "temporal confidence is clamped to this where something moved"
                     : method.splatting
                         ? "the splat methods' default: under motion their history carries the noise of how many splats land in "
                           "a pixel, which a higher cap compounds (docs/BENCHMARKS.md)"
                         : "temporal confidence is clamped to this where something moved"));
  {
    const float still = restir_options(eff).still_cap(method);
    out.push_back(make("still_confidence_cap", asked(req.has_still_confidence_cap(), format_float(req.still_confidence_cap())),
                       format_float(eff.still_confidence_cap()), temporal,
                       !method.reuse ? no_reuse
                       : !temporal   ? no_temporal
                                     : "confidence is clamped to " + format_float(still) +
                                         " where nothing moved since the previous frame (the camera and every instance), "
                                         "to confidence_cap elsewhere"));
  }
  out.push_back(make("spatial_neighbors", asked(req.has_spatial_neighbors(), u(req.spatial_neighbors())),
                     u(eff.spatial_neighbors()), method.reuse && eff.spatial_reuse(),
                     !method.reuse ? no_reuse
                     : !eff.spatial_reuse() ? no_spatial
                     : method.layers ? "neighbours per pixel (front layer only)" : "neighbours resampled per pixel"));
  out.push_back(make("spatial_radius", asked(req.has_spatial_radius(), format_float(req.spatial_radius())),
                     format_float(eff.spatial_radius()), spatial,
                     !method.reuse ? no_reuse : spatial ? "pixels around each pixel where neighbours are picked" +
                                      (req.has_spatial_radius() ? std::string()
                                                                 : "; default: " + format_float(100.0f * render::RestirOptions::spatial_radius_fraction) +
                                                                       "% of the image height, at least " +
                                                                       format_float(render::RestirOptions::spatial_radius_floor) +
                                                                       " px (the references use 20-32 px at 1080p)") : no_spatial));
  out.push_back(make("initial_candidates", asked(req.has_initial_candidates(), u(req.initial_candidates())),
                     u(eff.initial_candidates()), method.reuse, method.reuse ? "N_init paths per canonical sample" : no_reuse));
  out.push_back(make("light_candidates", asked(req.has_light_candidates(), u(req.light_candidates())),
                     u(eff.light_candidates()), method.reuse,
                     method.reuse ? "next-event-estimation candidates per path vertex" : no_reuse));
  {
    const uint32_t n = eff.disocclusion_spatial_neighbors();
    out.push_back(make("disocclusion_spatial_neighbors",
                       asked(req.has_disocclusion_spatial_neighbors(), u(req.disocclusion_spatial_neighbors())), u(n), spatial,
                       !method.reuse ? no_reuse
                       : !spatial    ? no_spatial
                       : n == 0 || n == eff.spatial_neighbors()
                           ? "pixels without history take spatial_neighbors like every other pixel"
                           : "neighbours for pixels whose reservoir holds no history (disoccluded, or the first frame), "
                             "instead of spatial_neighbors"));
  }
  const render::RestirOptions options = restir_options(eff);
  {
    // k layers: requested, measured, or (auto, before the first frame) assumed deep.
    const uint32_t k = layers_in_use(method, eff, measured_layers).value_or(2u);
    const uint32_t n = options.disocclusion_candidates(method, k);  // 0: no boost
    const bool splat_sort = temporal && method.splatting;
    out.push_back(make("disocclusion_initial_candidates",
                       asked(req.has_disocclusion_initial_candidates(), u(req.disocclusion_initial_candidates())), u(n),
                       splat_sort && n > 0,
                       !method.reuse        ? no_reuse
                       : !method.splatting  ? "splat methods only: the gather methods do not know before the initial pass which pixels get no history"
                       : !temporal          ? no_temporal
                       : n == 0             ? "pixels no splat reached take initial_candidates like every other pixel"
                       : method.layers      ? "candidate paths of the disoccluded pixels no splat reached: surfaces no deep domain held "
                                              "(" + m + "'s default " + u(method.disocclusion_initial_candidates) +
                                                  "; landing holes of surfaces in view take initial_candidates)"
                                            : "candidate paths of the pixels no splat reached (the splat sort runs before the initial pass; ML Fig. 9 \"more initial spp\")"));
  }
  const bool visibility_buffer = options.visibility_buffer(method.fixed_primary);
  out.push_back(make("direct_strata", asked(req.has_direct_strata(), u(req.direct_strata())), u(eff.direct_strata()),
                     method.reuse && options.direct_strata_used(method) > 1,
                     !method.reuse ? no_reuse + "; pt averages its spp camera samples"
                     : eff.direct_strata() == 1
                         ? "what the camera sees directly comes from each pixel's own camera sample"
                     : !visibility_buffer
                         ? "no visibility buffer to find the edges of directly seen emission (temporal and spatial reuse are off)"
                         : "pixels next to both emitting and non-emitting neighbours estimate what they see directly with " +
                               u(eff.direct_strata() * eff.direct_strata()) + " stratified camera samples"));
  out.push_back(make("albedo_strata", asked(req.has_albedo_strata(), u(req.albedo_strata())), u(eff.albedo_strata()),
                     method.reuse && options.albedo_strata_used(method) > 0,
                     !method.reuse ? no_reuse
                     : !method.fixed_primary
                         ? "the splat methods keep the camera sample in the sample; the control variate needs the domain's"
                     : eff.albedo_strata() == 1 ? "off: the reflected light comes from each pixel's own camera sample"
                         : "pixels whose neighbours see one surface in more than one material add the albedo control variate, "
                           "the pixel's earlier demodulated radiance times the difference between the mean albedo of " +
                               u(eff.albedo_strata() * eff.albedo_strata()) +
                               " stratified camera samples and the primary vertex's (docs/ARCHITECTURE.md)"));
  out.push_back(make("colour_cv", asked(req.has_colour_cv(), format_float(req.colour_cv())), format_float(eff.colour_cv()),
                     method.reuse && options.colour_cv_used(method) > 0.0f,
                     !method.reuse ? no_reuse
                     : method.layers
                         ? "not for restir-multilayer: its deep domains run the initial and spatial passes over the same pixels and "
                           "would write over the variate's per-pixel terms"
                     : eff.colour_cv() == 0.0f ? "off: each pixel's colour is that of the paths its reservoirs hold"
                     : !temporal && !eff.spatial_reuse()
                         ? "nothing to correct: without reuse the pixel's estimate is its initial paths'"
                         : "each pixel keeps its luminance and takes up to " + format_float(eff.colour_cv()) +
                               " of the way to the colour of its initial paths (less where their colours spread); the colour comes from the initial estimates of a " +
                               u(2 * gpu::COLOUR_CV_RADIUS + 1) + " x " + u(2 * gpu::COLOUR_CV_RADIUS + 1) +
                               " window, less the pixels whose reservoirs it reused (docs/ARCHITECTURE.md)"));
  out.push_back(make("temporal_filter", asked(req.experimental().has_temporal_filter(), on_off(req.experimental().temporal_filter())),
                     on_off(eff.experimental().temporal_filter()), temporal && !method.splatting,
                     !method.reuse ? no_reuse
                     : !temporal   ? no_temporal
                     : method.splatting ? "method " + m + " splats its history forward; the filter is for backprojection"
                     : eff.experimental().temporal_filter() ? "history only from a previous pixel whose centre surface is like this pixel's "
                                               "(normal, distance, material kind): a disoccluded pixel starts afresh"
                                             : "history from whatever the previous pixel saw"));

  // LoD mapping: decided from the scene when auto.
  {
    const auto mode = eff.lod_mapping();
    const std::string requested = asked_for("lod_mapping");
    const std::string groups = std::to_string(scene.lod_groups()) + " instance(s) with LoD levels";
    // The LOD paper's vertex mapping tau, inside the surface resolver: a UV-space structure per LoD
    // group, built only for scenes that have one and methods that keep history.
    const bool uv = method.reuse && temporal && scene.lod_groups() > 0 && mode != v1::LOD_MAPPING_OFF;
    std::string reason = !method.reuse                   ? no_reuse + " (the scene has " + groups + ")"
                         : !temporal                     ? no_temporal
                         : scene.lod_groups() == 0       ? "the scene has no instance with LoD levels: nothing switches"
                         : mode == v1::LOD_MAPPING_OFF   ? "a LoD switch refuses the temporal shifts of the switched instance's points (the scene has " + groups + ")"
                                                         : "points map across LoD switches through the shared UV parametrisation (LOD paper; the scene has " + groups + ")";
    out.push_back(make("lod_mapping", requested, uv ? "uv" : "off", uv, reason));
    out.push_back(make("lod_matching", asked_for("lod_matching"),
                       eff.experimental().lod_matching() ? "true" : "false", uv,
                       !uv ? "used by lod_mapping uv"
                       : eff.experimental().lod_matching() ? "UVs that several points share are matched by world distance (LOD Alg. 1)"
                                            : "UVs that several points share refuse the shift (LOD Fig. 6 without matching)"));
    out.push_back(make("lod_vertices", asked_for("lod_vertices"),
                       option_text(eff, "lod_vertices"), uv,
                       !uv ? "used by lod_mapping uv" : "the path vertices tau maps (LOD Fig. 5 ablation)"));
  }
  {
    const std::string requested = asked(req.has_layers(), req.layers() == 0 ? "auto" : u(req.layers()));
    const std::optional<uint32_t> k = layers_in_use(method, eff, measured_layers);
    std::string value = k ? u(*k) : "auto", reason = "method " + m + " has no pixel layers; used by multi-layer methods";
    if (method.layers && eff.layers() != 0) {
      reason = "requested";
    } else if (method.layers && measured_layers) {
      reason = "auto, measured on the scene's first frame: " + measured_layers->reason;
    } else if (method.layers) {
      reason = "auto: measured from the scene's visible depth complexity on its first frame (pixel-centre rays walked "
               "through their surfaces; a deep layer is kept while 10% of them reach it); every Frame's domain_init "
               "pass decision gives the count and the measured shares";
    }
    out.push_back(make("layers", requested, value, method.layers, reason));
    const std::string not_layers = "method " + m + " has no pixel layers; used by restir-multilayer";
    out.push_back(make("hole_fill_radius", asked(req.has_hole_fill_radius(), u(req.hole_fill_radius())), u(eff.hole_fill_radius()),
                       method.layers && eff.experimental().layer_mode() != v1::LAYER_MODE_UNIFORM,
                       !method.layers ? not_layers
                       : eff.experimental().layer_mode() == v1::LAYER_MODE_UNIFORM
                           ? "layer_mode uniform keeps every layer active: nothing to fill"
                           : "deep domains within this radius of a propagated one sample too, without propagating (ML 4.3; the paper uses 3)"));
    // The two rules that leave activated deep domains dormant (tracked, not sampled): layer_mode active only.
    auto dormancy = [&](const std::string& name, bool has, uint32_t req_value, uint32_t eff_value, const std::string& off,
                        const std::string& on) {
      out.push_back(make(name, asked(has, u(req_value)), u(eff_value), method.layers && eff.experimental().layer_mode() == v1::LAYER_MODE_ACTIVE && eff_value > 0,
                         !method.layers                                 ? not_layers
                         : eff.experimental().layer_mode() != v1::LAYER_MODE_ACTIVE ? "only layer_mode active has dormant domains (the validation variants are the ML paper's)"
                         : eff_value == 0                               ? off
                                                                        : on));
    };
    dormancy("silhouette_band", req.has_silhouette_band(), req.silhouette_band(), eff.silhouette_band(),
             "off: every activated deep domain samples (ML 4.3)",
             std::string(eff.reveal_lookahead() > 0 ? "deep domains without a reveal prediction (no motion known) farther" : "deep domains farther") +
                 " than this from a silhouette of the front layer are tracked (their representative hits propagate) but sample "
                 "nothing until an edge comes this near (not in the ML paper; docs/BENCHMARKS.md)");
    dormancy("reveal_lookahead", req.has_reveal_lookahead(), req.reveal_lookahead(), eff.reveal_lookahead(),
             "off: the silhouette band alone decides which activated deep domains sample",
             "a deep domain samples when, moving against the front layer as over the last frame, it is uncovered within this many "
             "frames; otherwise it is tracked but samples nothing (not in the ML paper; docs/BENCHMARKS.md: a fifth of the silhouette "
             "band's deep domains at its coverage and error under carousel's pan)");
    const bool deep_backup_used = method.layers && eff.experimental().layer_mode() == v1::LAYER_MODE_ACTIVE && temporal && eff.experimental().deep_backup();
    out.push_back(make("deep_backup", asked_for("deep_backup"),
                       eff.experimental().deep_backup() ? "true" : "false", deep_backup_used,
                       !method.layers ? not_layers
                       : eff.experimental().layer_mode() != v1::LAYER_MODE_ACTIVE
                           ? "only layer_mode active (the validation variants are the ML paper's: splats only)"
                       : !temporal          ? no_temporal
                       : !eff.experimental().deep_backup() ? "off: a disoccluded pixel has history only where a deep splat lands (ML 4.2)"
                                            : "a disoccluded pixel whose hit an active previous deep domain held takes that domain's "
                                              "reservoir as a backup sample (RS-main 4.2 across layers; not in the ML paper)"));
    out.push_back(make("layer_mode", asked_for("layer_mode"), option_text(eff, "layer_mode"),
                       method.layers,
                       !method.layers ? not_layers
                       : eff.experimental().layer_mode() == v1::LAYER_MODE_ACTIVE
                           ? "active domains propagated by representative hits, depth ranges (ML)"
                           : "a validation variant of the ML paper (Fig. 5, Table 1)"));
  }
  out.push_back(make("splats_per_frame", asked(req.has_splats_per_frame(), u(req.splats_per_frame())),
                     u(eff.splats_per_frame()), method.splatting,
                     method.splatting ? "K splats per frame over the shutter interval (motion blur)"
                                      : "method " + m + " does not splat; used by restir-splat methods"));
  {
    // Motion blur (RS-main 4.4) for every method; FrameInput.camera.shutter > 0 opens it per frame.
    std::string how = "pt integrates each pixel over the shutter (time sampled uniformly)";
    if (method.splatting) how = "reservoirs keep their time and splat into K = splats_per_frame time partitions (RS-main Eq. 19)";
    else if (method.reuse) how = "reservoirs keep their time offset; backprojection uses the motion at the frame's instant (RS-main 4.4.1)";
    out.push_back(make("motion_blur", "", "shutter", true,
                       "FrameInput.camera.shutter > 0 opens the shutter on the way from the previous frame's camera; " + how));
  }

  // Features of the path tracer that follow from the scene.
  const bool png = std::find(encodings.begin(), encodings.end(), v1::IMAGE_ENCODING_PNG_PREVIEW) != encodings.end();
  out.push_back(make("exposure", asked(req.has_exposure(), format_float(req.exposure())), format_float(eff.exposure()), png,
                     png ? "stops applied before the ACES curve of PNG previews" : "no PNG_PREVIEW encoding requested"));
  uint64_t point_and_spot = 0, directional = 0;
  for (const auto& l : scene.lights()) (l.type() == "directional" ? directional : point_and_spot) += 1;
  const bool nee = scene.emissive_triangles() > 0 || scene.lights_size() > 0 || scene.environment_light();
  std::string lights = std::to_string(scene.emissive_triangles()) + " emissive triangles";
  if (scene.lights_size() > 0)
    lights += " + " + std::to_string(point_and_spot) + " point and spot lights + " + std::to_string(directional) +
              " directional lights";
  if (scene.environment_light())
    lights += scene.environment_map().empty()
                  ? " + the environment"
                  : " + the environment map " + scene.environment_map() + ", by luminance x solid angle, its share of the choices by power";
  out.push_back(make("next_event_estimation", "", nee ? "on" : "off", nee,
                     nee ? "light sampling over " + lights : "the scene has no emissive triangles, no lights and a black environment"));
  {
    // light_sampler auto: the tree where the scene has many bounded lights (render/light_sampler_choice.h).
    const uint64_t bounded = scene.emissive_triangles() + point_and_spot;
    const render::LightSampler asked_sampler = options.light_sampler;  // the option table's mapping
    const bool tree = render::light_sampler_in_use(asked_sampler, bounded) == render::LightSampler::tree;
    const bool auto_tree = render::light_sampler_in_use(render::LightSampler::automatic, bounded) == render::LightSampler::tree;
    const std::string count = std::to_string(bounded) + " bounded lights (emissive triangles, point and spot lights)";
    const std::string threshold = std::to_string(render::k_auto_light_tree_min_lights);
    std::string reason =
        asked_sampler != render::LightSampler::automatic
            ? std::string("as asked; auto would take ") + (auto_tree ? "tree" : "power") + " for the scene's " + count
        : tree ? "auto: the scene has " + count + ", at least " + threshold +
                     ": the light tree picks near and facing lights at each shading point (night-street, 822: 0.29x power's "
                     "error at equal time, docs/BENCHMARKS.md)"
               : "auto: the scene has " + count + ", fewer than " + threshold +
                     ": the alias table by power (with a few lights the tree has little to choose and costs 1-9% a frame)";
    out.push_back(make("light_sampler", asked_for("light_sampler"), tree ? "tree" : "power", nee, nee ? reason : "no next-event estimation"));
  }
  out.push_back(make("thin_lens", "", scene.thin_lens() ? "on" : "off", true,
                     scene.thin_lens() ? "the scene camera has an aperture; FrameInput.camera.aperture = 0 turns it off"
                                       : "the scene camera is a pinhole; FrameInput.camera.aperture > 0 turns it on"));

  // The table's verdict on the method: an option outside its scope never applies; an option without
  // a decision above gets one.
  for (const auto& row : options::option_table()) {
    auto it = std::find_if(out.begin(), out.end(), [&](const v1::Decision& d) { return d.name() == row.name; });
    if (it == out.end()) {
      out.push_back(make(row.name, asked_for(row.name), options::value_text(row, options::get_value(eff, row)), true,
                         row.help));
      it = out.end() - 1;
    }
    if (!options::applies(row, method)) {
      it->set_applies(false);
      it->set_reason(options::not_applying_reason(row, method));
    }
  }
  return out;
}

}  // namespace strata::service
