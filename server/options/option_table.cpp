#include "options/option_table.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <type_traits>

namespace strata::options {
namespace {

using render::RestirOptions;

template <auto M>
double get_member(const RestirOptions& o) {
  using T = std::remove_cvref_t<decltype(o.*M)>;
  if constexpr (std::is_enum_v<T>) return double(static_cast<uint32_t>(o.*M));
  else return double(o.*M);
}

template <auto M>
void set_member(RestirOptions& o, double v) {
  using T = std::remove_cvref_t<decltype(o.*M)>;
  if constexpr (std::is_enum_v<T>) o.*M = static_cast<T>(uint32_t(v));
  else if constexpr (std::is_same_v<T, bool>) o.*M = v != 0.0;
  else o.*M = static_cast<T>(v);
}

#define STRATA_MEMBER(m) .get = &get_member<&RestirOptions::m>, .set = &set_member<&RestirOptions::m>

using render::LayerMode;
using render::LightSampler;
using render::LodMapping;
using render::LodVertices;
using render::Mis;
using render::Shift;
using render::Suffix;

constexpr uint32_t u(auto e) { return static_cast<uint32_t>(e); }

// The proto numbers are those of render.proto's enums (0 is UNSPECIFIED: the default).
constexpr Choice k_shift[] = {
    {"reconnection", 1, u(Shift::reconnection), "reconnect at x_2 only (the base path must allow it)"},
    {"hybrid", 2, u(Shift::hybrid), "random replay until the first reconnectable vertex"},
};
constexpr Choice k_mis[] = {
    {"balance", 1, u(Mis::balance), "generalized balance heuristic (RS-main Eq. 6), O(N^2) shifts"},
    {"pairwise", 2, u(Mis::pairwise), "confidence-weighted pairwise MIS, O(N) shifts"},
};
constexpr Choice k_suffix[] = {
    {"auto", 1, u(Suffix::automatic), "replay, but keep a one-segment suffix whose ray misses every changed instance's swept box (exact)"},
    {"replay", 2, u(Suffix::replay), "trace it again in the target frame, both directions (unbiased)"},
    {"cached", 3, u(Suffix::cached), "keep the stored radiance, as the reference implementations do (biased)"},
    {"fail", 4, u(Suffix::fail), "refuse the shift (temporal.stale)"},
};
constexpr Choice k_lod_mapping[] = {
    {"auto", 1, u(LodMapping::automatic), "uv when the scene has LoD groups, else off"},
    {"off", 2, u(LodMapping::off), "a LoD switch refuses the temporal shifts of the switched instance's points"},
    {"uv", 3, u(LodMapping::uv), "the vertex mapping tau through the shared UV parametrisation (the LOD paper)"},
};
constexpr Choice k_light_sampler[] = {
    {"auto", 3, u(LightSampler::automatic), "tree where the scene has at least 16 bounded lights (emissive triangles, point and spot lights), else power"},
    {"power", 1, u(LightSampler::power), "an alias table by power: every light's probability the same everywhere"},
    {"tree", 2, u(LightSampler::tree),
     "the light tree: near and facing lights more often, by importance at the shading point (Conty Estevez & Kulla 2018)"},
};
constexpr Choice k_lod_vertices[] = {
    {"both", 1, u(LodVertices::both), "the primary hit and the reconnection vertex"},
    {"primary", 2, u(LodVertices::primary), "the primary hit only (splat reprojection, gather backprojection)"},
    {"reconnection", 3, u(LodVertices::reconnection), "the reconnection vertex only"},
};
constexpr Choice k_layer_mode[] = {
    {"active", 1, u(LayerMode::active), "active domains propagated by representative hits, depth ranges (ML)"},
    {"uniform", 2, u(LayerMode::uniform), "every layer of every pixel active (ML Fig. 5)"},
    {"no-depth-ranges", 3, u(LayerMode::no_depth_ranges), "active domains, layers found by stepping rays (ML Table 1 \"w/o ranges\")"},
};

const OptionSpec k_table[] = {
    // Every method.
    {.name = "spp", .scope = Scope::every, .lo = 1, .limit = "max_spp", .default_from = DefaultFrom::member, .fixed_default = 1,
     .flag = "--spp", .help = "samples per pixel per frame; the restir-* methods keep one reservoir per pixel and take only 1",
     .sets = "RenderSettings::spp: the path tracer's samples per dispatch"},
    {.name = "max_depth", .scope = Scope::every, .lo = 1, .limit = "max_depth", .default_from = DefaultFrom::service_limit,
     .fixed_default = 16, .flag = "--max-depth", .help = "path segments after the camera (restir-di: at most 2)",
     .sets = "GpuFrameConstants.max_depth, GpuRestirConstants.max_segments"},
    {.name = "light_sampler", .kind = Kind::choice, .scope = Scope::every, .choices = k_light_sampler, .flag = "--light-sampler",
     .help = "how next-event estimation (pt's, and the restir-* methods' light candidates) chooses a light",
     .sets = "SPEC_LIGHT_TREE, the scene's light tree buffers (GpuScene)", STRATA_MEMBER(light_sampler)},
    {.name = "exposure", .kind = Kind::real, .scope = Scope::every, .on_change = OnChange::in_place, .lo = -64, .hi = 64,
     .unit = "stops", .fixed_default = 0, .flag = "--exposure", .help = "exposure of PNG previews, before the ACES curve",
     .sets = "nothing on the device: the PNG encoder"},
    // The restir-* methods.
    {.name = "initial_candidates", .lo = 1, .hi = gpu::RESTIR_MAX_INITIAL_CANDIDATES, .limit = "RESTIR_MAX_INITIAL_CANDIDATES",
     .flag = "--initial-candidates", .help = "N_init candidate paths per canonical sample",
     .sets = "GpuRestirConstants.initial_candidates", STRATA_MEMBER(initial_candidates)},
    {.name = "light_candidates", .lo = 1, .hi = gpu::RESTIR_MAX_LIGHT_CANDIDATES, .limit = "RESTIR_MAX_LIGHT_CANDIDATES",
     .flag = "--light-candidates", .help = "next-event-estimation samples per path vertex",
     .sets = "GpuRestirConstants.light_candidates", STRATA_MEMBER(light_candidates)},
    {.name = "temporal_reuse", .kind = Kind::flag, .flag = "--no-temporal", .negated_flag = true,
     .help = "reuse the previous frame's reservoirs (gather: backprojection; splat methods: splatting)",
     .sets = "the temporal stage and its buffers", STRATA_MEMBER(temporal)},
    {.name = "spatial_reuse", .kind = Kind::flag, .flag = "--no-spatial", .negated_flag = true,
     .help = "reuse the neighbours' reservoirs", .sets = "the spatial stage and its buffers", STRATA_MEMBER(spatial)},
    {.name = "confidence_cap", .kind = Kind::real, .lo = gpu::RESTIR_MIN_CONFIDENCE_CAP, .hi = gpu::RESTIR_MAX_CONFIDENCE_CAP,
     .limit = "RESTIR_MAX_CONFIDENCE_CAP", .default_from = DefaultFrom::method, .default_text = "the method's: 2 (restir-di: 4); method auto: 4 where pt's error per sample shows the light is hard to find",
     .flag = "--confidence-cap", .help = "cap of the temporal history's confidence where something moved",
     .sets = "GpuRestirConstants.confidence_cap", STRATA_MEMBER(confidence_cap), .restir_zero = "the method's"},
    {.name = "still_confidence_cap", .kind = Kind::real, .lo = gpu::RESTIR_MIN_CONFIDENCE_CAP, .hi = gpu::RESTIR_MAX_CONFIDENCE_CAP,
     .zero = "confidence_cap", .limit = "RESTIR_MAX_CONFIDENCE_CAP", .flag = "--still-confidence-cap",
     .help = "confidence cap where nothing moved since the previous frame (the camera and every instance)",
     .sets = "GpuRestirConstants.still_confidence_cap", STRATA_MEMBER(still_confidence_cap)},
    {.name = "spatial_neighbors", .hi = gpu::RESTIR_MAX_SPATIAL_NEIGHBORS, .limit = "RESTIR_MAX_SPATIAL_NEIGHBORS",
     .flag = "--spatial-neighbors", .help = "neighbours resampled per pixel (restir-multilayer: front layer only)",
     .sets = "GpuRestirConstants.spatial_neighbors", STRATA_MEMBER(spatial_neighbors)},
    {.name = "spatial_radius", .kind = Kind::real, .lo = gpu::RESTIR_MIN_SPATIAL_RADIUS, .hi = gpu::RESTIR_MAX_SPATIAL_RADIUS,
     .limit = "RESTIR_MAX_SPATIAL_RADIUS", .unit = "pixels", .default_from = DefaultFrom::image_height,
     .default_text = "2.5% of the image height, at least 4", .flag = "--spatial-radius",
     .help = "radius of the spatial neighbourhood", .sets = "GpuRestirConstants.spatial_radius", STRATA_MEMBER(spatial_radius),
     .restir_zero = "automatic"},
    {.name = "disocclusion_spatial_neighbors", .hi = gpu::RESTIR_MAX_SPATIAL_NEIGHBORS, .zero = "spatial_neighbors",
     .limit = "RESTIR_MAX_SPATIAL_NEIGHBORS", .flag = "--disocclusion-spatial-neighbors",
     .help = "neighbours for pixels without history (disoccluded, first frame)",
     .sets = "GpuRestirConstants.disocclusion_spatial_neighbors", STRATA_MEMBER(disocclusion_spatial_neighbors)},
    {.name = "direct_strata", .lo = 1, .hi = gpu::RESTIR_MAX_DIRECT_STRATA, .limit = "RESTIR_MAX_DIRECT_STRATA",
     .flag = "--direct-strata",
     .help = "G: pixels at the edge of directly seen emission take G x G stratified camera samples for it",
     .sets = "GpuRestirConstants.direct_strata", STRATA_MEMBER(direct_strata)},
    {.name = "lod_mapping", .kind = Kind::choice, .choices = k_lod_mapping, .flag = "--lod-mapping",
     .help = "LoD-aware reuse: mapping path vertices between LoD levels (the LOD paper)",
     .sets = "the surface resolver's UV-space structure (GpuScene::set_lod_mapping)", STRATA_MEMBER(lod_mapping)},
    {.name = "albedo_strata", .scope = Scope::fixed_primary, .lo = 1, .hi = gpu::RESTIR_MAX_DIRECT_STRATA,
     .limit = "RESTIR_MAX_DIRECT_STRATA", .flag = "--albedo-strata",
     .help = "G: pixels at albedo edges on one surface add the albedo control variate with G x G stratified camera samples (1: off)",
     .sets = "GpuRestirConstants.albedo_strata", STRATA_MEMBER(albedo_strata)},
    {.name = "colour_cv", .kind = Kind::real, .scope = Scope::colour_cv, .lo = 0, .hi = 1, .zero = "off", .flag = "--colour-cv",
     .help = "largest b of the colour control variate: each pixel keeps its luminance and takes up to b of the way from its "
             "colour to that of its initial paths, less where their colours spread",
     .sets = "GpuRestirConstants.colour_cv", STRATA_MEMBER(colour_cv)},
    {.name = "splats_per_frame", .scope = Scope::splatting, .lo = 1, .hi = gpu::RESTIR_MAX_SPLATS_PER_FRAME,
     .limit = "RESTIR_MAX_SPLATS_PER_FRAME", .flag = "--splats-per-frame",
     .help = "K time partitions of an open shutter (motion blur, RS-main Eq. 19)",
     .sets = "GpuFrameConstants.splats_per_frame, GpuRestirConstants.splats_per_frame", STRATA_MEMBER(splats_per_frame)},
    {.name = "disocclusion_initial_candidates", .scope = Scope::splatting, .hi = gpu::RESTIR_MAX_INITIAL_CANDIDATES,
     .zero = "the method's: 8 for restir-multilayer, else initial_candidates", .limit = "RESTIR_MAX_INITIAL_CANDIDATES",
     .flag = "--disocclusion-initial-candidates",
     .help = "candidate paths of pixels no splat reached (ML Fig. 9 \"more initial spp\"; restir-multilayer: of its disoccluded "
             "pixels); equal to initial_candidates: off",
     .sets = "GpuRestirConstants.disocclusion_initial_candidates", STRATA_MEMBER(disocclusion_initial_candidates)},
    {.name = "layers", .scope = Scope::layers, .hi = gpu::LAYERS_MAX,
     .zero = "auto, measured from the scene's visible depth complexity on its first frame", .limit = "LAYERS_MAX",
     .flag = "--layers", .help = "k pixel layers per pixel", .sets = "GpuRestirConstants.layers and every per-domain buffer's size",
     STRATA_MEMBER(layers)},
    {.name = "hole_fill_radius", .scope = Scope::layers, .hi = gpu::RESTIR_MAX_HOLE_FILL_RADIUS, .zero = "off",
     .limit = "RESTIR_MAX_HOLE_FILL_RADIUS", .unit = "pixels", .flag = "--hole-fill-radius",
     .help = "deep domains within this many pixels of a propagated one sample too (ML 4.3)",
     .sets = "GpuRestirConstants.hole_fill_radius", STRATA_MEMBER(hole_fill_radius)},
    {.name = "silhouette_band", .scope = Scope::layers, .hi = gpu::RESTIR_MAX_SILHOUETTE_BAND, .zero = "off",
     .limit = "RESTIR_MAX_SILHOUETTE_BAND", .unit = "pixels", .flag = "--silhouette-band",
     .help = "deep domains farther than this from a silhouette of the front layer are dormant (tracked, not sampled)",
     .sets = "domain_fill.comp's band", STRATA_MEMBER(silhouette_band)},
    {.name = "reveal_lookahead", .scope = Scope::layers, .hi = gpu::RESTIR_MAX_REVEAL_LOOKAHEAD, .zero = "off",
     .limit = "RESTIR_MAX_REVEAL_LOOKAHEAD", .unit = "frames", .flag = "--reveal-lookahead",
     .help = "a deep domain whose motion against the front layer is known samples when predicted to be uncovered within this "
             "many frames, else it is dormant",
     .sets = "domain_build.comp's lookahead", STRATA_MEMBER(reveal_lookahead)},

    // Experimental: the papers' validation variants and ablations.
    {.name = "shift", .group = Group::experimental, .kind = Kind::choice, .choices = k_shift, .flag = "--shift",
     .help = "shift mapping between pixels' paths (RS-main 3)", .sets = "GpuRestirConstants.shift_mode", STRATA_MEMBER(shift)},
    {.name = "mis", .group = Group::experimental, .kind = Kind::choice, .choices = k_mis, .flag = "--mis",
     .help = "MIS weights of spatial resampling", .sets = "GpuRestirConstants.mis_mode", STRATA_MEMBER(mis)},
    {.name = "unbiased", .group = Group::experimental, .kind = Kind::flag, .flag = "--biased", .negated_flag = true,
     .help = "MIS weights for the temporal pair; off: the DI tutorial's confidence-only temporal weights (biased)",
     .sets = "GpuRestirConstants.flags RESTIR_UNBIASED", STRATA_MEMBER(unbiased)},
    {.name = "suffix", .group = Group::experimental, .kind = Kind::choice, .choices = k_suffix, .flag = "--suffix",
     .help = "what temporal reuse does with the path after its reconnection vertex when the scene changed",
     .sets = "GpuRestirConstants.suffix_mode", STRATA_MEMBER(suffix)},
    {.name = "temporal_filter", .group = Group::experimental, .kind = Kind::flag, .scope = Scope::fixed_primary,
     .flag = "--no-temporal-filter", .negated_flag = true,
     .help = "history only from a previous pixel that saw a like surface (normal, distance, material kind)",
     .sets = "GpuRestirConstants.flags RESTIR_TEMPORAL_FILTER", STRATA_MEMBER(temporal_filter)},
    {.name = "lod_matching", .group = Group::experimental, .kind = Kind::flag, .flag = "--lod-matching",
     .help = "lod_mapping uv: UVs several points share are matched greedily (LOD Alg. 1), else refused",
     .sets = "GpuScene::set_lod_mapping", STRATA_MEMBER(lod_matching)},
    {.name = "lod_vertices", .group = Group::experimental, .kind = Kind::choice, .choices = k_lod_vertices,
     .flag = "--lod-vertices", .help = "lod_mapping uv: the path vertices tau maps (LOD Fig. 5)",
     .sets = "GpuScene::set_lod_mapping", STRATA_MEMBER(lod_vertices)},
    {.name = "colour_cv_spread", .group = Group::experimental, .kind = Kind::real, .scope = Scope::colour_cv, .lo = 0,
     .hi = 1000, .zero = "b = colour_cv everywhere", .flag = "--colour-cv-spread",
     .help = "k of the colour control variate's b = colour_cv k / (k + S), S the spread of the window's initial colours",
     .sets = "GpuRestirConstants.colour_cv_spread", STRATA_MEMBER(colour_cv_spread)},
    {.name = "layer_mode", .group = Group::experimental, .kind = Kind::choice, .scope = Scope::layers, .choices = k_layer_mode,
     .flag = "--layer-mode", .help = "how pixel-layer domains are chosen and how a splat finds its layer (ML validation variants)",
     .sets = "GpuRestirConstants.layer_mode", STRATA_MEMBER(layer_mode)},
    {.name = "deep_backup", .group = Group::experimental, .kind = Kind::flag, .scope = Scope::layers, .flag = "--deep-backup",
     .help = "layer_mode active: a disoccluded pixel takes the reservoir of the previous deep domain that held its hit as a "
             "backup sample (RS-main 4.2 across layers)",
     .sets = "restir_splat_resample.comp's backup", STRATA_MEMBER(deep_backup)},
    {.name = "view_layer", .group = Group::experimental, .scope = Scope::layers, .hi = gpu::LAYERS_MAX - 1, .zero = "the image",
     .limit = "LAYERS_MAX - 1", .flag = "--view-layer",
     .help = "write each pixel's layer-i domain estimate instead of the image (ML Eq. 3; 0 where that domain is inactive)",
     .sets = "GpuRestirConstants.view_layer", STRATA_MEMBER(view_layer)},
};

#undef STRATA_MEMBER

// 1000 as "1000", 0.6 as "0.6": the shortest %g form that reads back as the same float.
std::string number(double v) {
  char buf[48];
  for (int precision = 6; precision <= 9; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (!std::isfinite(v) || float(std::strtod(buf, nullptr)) == float(v)) break;
  }
  return buf;
}

}  // namespace

std::span<const OptionSpec> option_table() { return k_table; }

const OptionSpec* find_option(std::string_view name) {
  for (const auto& o : k_table)
    if (name == o.name) return &o;
  return nullptr;
}

bool applies(const OptionSpec& o, const render::MethodSpec& m) {
  switch (o.scope) {
    case Scope::every: return true;
    case Scope::reuse: return m.reuse;
    case Scope::splatting: return m.splatting;
    case Scope::layers: return m.layers;
    case Scope::fixed_primary: return m.reuse && m.fixed_primary;
    case Scope::colour_cv: return m.reuse && (m.fixed_primary || (m.splatting && !m.layers));
  }
  return false;
}

std::string scope_text(Scope s) {
  switch (s) {
    case Scope::every: return "every method";
    case Scope::reuse: return "the restir-* methods";
    case Scope::splatting: return "the splat methods (restir-splat, restir-splat-backup, restir-multilayer)";
    case Scope::layers: return "restir-multilayer (pixel layers)";
    case Scope::fixed_primary: return "the gather methods (restir-gather, restir-di)";
    case Scope::colour_cv: return "restir-gather, restir-di, restir-splat, restir-splat-backup";
  }
  return "";
}

std::string not_applying_reason(const OptionSpec& o, const render::MethodSpec& m) {
  std::string why;
  switch (o.scope) {
    case Scope::every: break;
    case Scope::reuse: why = "has no reuse"; break;
    case Scope::splatting: why = "does not splat"; break;
    case Scope::layers: why = "has no pixel layers"; break;
    case Scope::fixed_primary: why = m.reuse ? "splats its history forward (no fixed primary vertex)" : "has no reuse"; break;
    case Scope::colour_cv:
      why = !m.reuse ? "has no reuse"
                     : "keeps deep domains that run the initial and spatial passes over the same pixels and would write over the "
                       "variate's per-pixel terms";
      break;
  }
  return "method " + std::string(m.name) + " " + why + "; used by " + scope_text(o.scope);
}

double default_value(const OptionSpec& o) { return o.get ? o.get(RestirOptions{}) : o.fixed_default; }

const Choice* find_choice(const OptionSpec& o, double v, bool by_proto) {
  for (const auto& c : o.choices)
    if ((by_proto ? double(c.proto) : double(c.value)) == v) return &c;
  return nullptr;
}

std::string value_text(const OptionSpec& o, double v) {
  switch (o.kind) {
    case Kind::count: return std::to_string(uint64_t(v));
    case Kind::real: return number(v);
    case Kind::flag: return v != 0.0 ? "true" : "false";
    case Kind::choice: {
      const Choice* c = find_choice(o, v, false);
      return c ? c->name : std::to_string(int64_t(v));
    }
  }
  return "";
}

std::optional<double> parse_value(const OptionSpec& o, const std::string& text) {
  try {
    size_t end = 0;
    switch (o.kind) {
      case Kind::count: {
        if (text.empty() || text[0] == '-') return std::nullopt;
        const unsigned long long v = std::stoull(text, &end);
        if (end != text.size() || v > UINT32_MAX) return std::nullopt;
        return double(v);
      }
      case Kind::real: {
        const float v = std::stof(text, &end);
        if (end != text.size()) return std::nullopt;
        return double(v);
      }
      case Kind::flag:
        if (text == "true" || text == "1") return 1.0;
        if (text == "false" || text == "0") return 0.0;
        return std::nullopt;
      case Kind::choice:
        for (const auto& c : o.choices)
          if (text == c.name) return double(c.value);
        return std::nullopt;
    }
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

void set_choice(render::RestirOptions& r, std::string_view option, const std::string& name) {
  const OptionSpec* o = find_option(option);
  const std::optional<double> v = o && o->kind == Kind::choice ? parse_value(*o, name) : std::nullopt;
  if (!v) throw std::invalid_argument(std::string(option) + " = '" + name + "' is not one of: " + (o ? range_text(*o) : "(no such option)"));
  o->set(r, *v);
}

std::string range_text(const OptionSpec& o, double hi_override) {
  switch (o.kind) {
    case Kind::flag: return "true | false";
    case Kind::choice: {
      std::string s;
      for (const auto& c : o.choices) s += (s.empty() ? "" : " | ") + std::string(c.name);
      return s;
    }
    default: break;
  }
  const double hi = hi_override > 0.0 ? hi_override : o.hi;
  std::string s = "[" + number(o.lo) + ", " + (o.limit && hi_override == 0.0 && o.hi == 0.0 ? std::string(o.limit) : number(hi)) + "]";
  if (o.unit) s += std::string(" ") + o.unit;
  if (o.zero) s += std::string(" (0 = ") + o.zero + ")";
  return s;
}

std::string range_error(const OptionSpec& o, double v, const std::string& field, double hi_override, bool restir) {
  if (o.kind == Kind::flag) return "";
  if (o.kind == Kind::choice) {
    if (find_choice(o, v, false)) return "";
    std::string names;
    for (const auto& c : o.choices) names += (names.empty() ? "" : ", ") + std::string(c.name);
    return field + " = " + std::to_string(int64_t(v)) + " is not one of " + names;
  }
  const double hi = hi_override > 0.0 ? hi_override : o.hi;
  const bool zero_ok = v == 0.0 && (o.zero || (restir && o.restir_zero));
  if (zero_ok || (std::isfinite(v) && v >= o.lo && v <= hi)) return "";
  std::string text = o.kind == Kind::count ? std::to_string(int64_t(v)) : number(v);
  std::string s = field + " = " + text + " is outside [" + number(o.lo) + ", " + number(hi) + "]";
  if (o.unit) s += std::string(" ") + o.unit;
  std::string notes;
  if (o.zero) notes = std::string("0 = ") + o.zero;
  else if (restir && o.restir_zero) notes = std::string("0 = ") + o.restir_zero;
  if (o.limit) notes += (notes.empty() ? "limit " : "; limit ") + std::string(o.limit);
  return notes.empty() ? s : s + " (" + notes + ")";
}

}  // namespace strata::options

namespace strata::render {

void RestirOptions::validate() const {
  for (const auto& o : options::option_table()) {
    if (!o.get) continue;
    const std::string error = options::range_error(o, o.get(*this), "restir." + std::string(o.name), 0.0, /*restir=*/true);
    if (!error.empty()) throw std::invalid_argument(error);
  }
}

}  // namespace strata::render
