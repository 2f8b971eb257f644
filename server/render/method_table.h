#pragma once
// The method table: every rendering method is one row, and everything that depends on which
// method a session or `stratad render` asked for reads that row (construction, option
// validation, the session's decisions, the CLI help). No method name is compared anywhere else.
// Adding a method is one row here plus whatever new stages it composes (docs/ARCHITECTURE.md).
#include <string>
#include <string_view>
#include <vector>

namespace strata::render {

// How a method reuses the previous frame (MethodSpec::temporal; docs/ARCHITECTURE.md, "The frame").
enum class StageKind {
  path_trace,       // pt: no reuse, the reference path tracer
  temporal_gather,  // the previous reservoir at the backprojected pixel (Lin 2022 section 7)
  temporal_splat,   // previous reservoirs splatted forward and sorted by pixel (RS-supp 3.1), then resampled (RS-main 4.1)
};

struct MethodSpec {
  const char* name;
  const char* summary;       // one line: CLI help and the session's `method` decision
  bool reuse;                // resampling with reservoirs kept between frames (history)
  bool direct_lighting;      // one-bounce paths (ReSTIR DI)
  bool splatting;            // temporal reuse by splatting: `splats_per_frame` applies
  bool backup;               // splatting with the backprojected backup sample (RS-main 4.2)
  bool layers;               // pixel-layer domains (the ML paper): `layers` applies
  StageKind temporal;        // the temporal stage (reuse methods): temporal_gather or temporal_splat
  // A domain's primary vertex is fixed per frame (the visibility buffer's camera sample): shifts
  // start there instead of tracing the sample's camera ray (docs/ARCHITECTURE.md, "Domains and
  // their primary vertex"). Not for splatting, whose samples carry their primary hits.
  bool fixed_primary;
  // The default cap of the temporal history's confidence where something moved (RestirOptions::
  // confidence_cap = 0). Chosen by measurement (docs/ARCHITECTURE.md, "Confidence cap"): 2 for
  // restir-gather and the splat methods, 4 for restir-di (2 and 4 tie there).
  float confidence_cap;
  // The default of RestirOptions::disocclusion_initial_candidates (0 there): the candidate paths of
  // a disoccluded pixel that no splat reached. 8 for restir-multilayer, whose deep domains cover most
  // disoccluded pixels, so that the few left uncovered (surfaces no layer held: new ones, and those
  // the activation missed) take 8 paths, at little cost (docs/ARCHITECTURE.md, "Pixel layers");
  // 0 (initial_candidates) for the others, where every landing hole would pay for it.
  uint32_t disocclusion_initial_candidates;
};

const std::vector<MethodSpec>& method_table();
// The row of `name`; std::invalid_argument naming `field` and the methods when there is none.
const MethodSpec& method_spec(const std::string& name, const std::string& field = "method");
std::vector<std::string> available_methods();
// "pt, restir-gather, ..." for messages and help.
std::string method_names();
// One line per method, "name: summary", for --help.
std::string method_help();
// The method `stratad render` uses when none is named. A session's default is `method auto`
// (service/method_auto.h), which measures pt and this method on the session's scene and keeps the
// one with the lower error at equal time; `stratad render` renders in-process without that
// calibration and takes the ReSTIR method the service is built for.
inline constexpr const char* k_default_method = "restir-gather";

}  // namespace strata::render
