// `strata eval`: error against run time. For each scene, gets the converged reference of
// every frame of its default animation, or of a camera path (eval_frames.h), from stratad
// (RenderReference, cached by the server), plays the frames with each method, scores every frame
// against its reference (RelMSE, MAPE, HDR-FLIP; also over the disoccluded pixels when the
// reference has them), and writes results.csv, results.json and a self-contained report.html.
// With --equal-time, pt then gets as many samples per frame as fit in each other method's median
// frame time. With --score-from N the first N frames warm each method up: they are played but
// neither scored nor timed, and need no reference. A --methods entry may carry ReSTIR flags of its
// own (eval_method.h); --save-frames keeps every scored frame and its reference as EXR.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "eval_frames.h"
#include "eval_runner.h"
#include "eval_scoring.h"
#include "progress.h"
#include "report/report.h"

namespace strata::client {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct EvalArgs : EvalSettings {
  std::string scene_list = "cornell", method_list = "pt,restir-gather";
  float exposure = 0.0f;  // PNG insets
  bool save_frames = false;  // --save-frames: every scored frame and its reference as EXR
  float shutter_value = 0.0f;     // --shutter, when given
  uint32_t splats_value = 1;      // --splats-per-frame, when given
};

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream ss(list);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

// The command line that reproduces this evaluation (every setting explicit).
std::string command_line(const EvalArgs& a) {
  std::ostringstream s;
  s << "strata eval --server " << a.conn.server << " --scenes " << a.scene_list << " --methods " << a.method_list;
  if (a.camera_path.empty()) s << " --frames " << a.frames;
  else s << " --camera-path " << a.camera_path;
  if (a.score_from) s << " --score-from " << a.score_from;
  s << " --width " << a.width << " --height " << a.height << " --reference-spp " << a.reference_spp << " --reference-error "
    << a.reference_error << " --seed " << a.seed;
  if (a.max_depth) s << " --max-depth " << a.max_depth;
  if (a.shutter) s << " --shutter " << *a.shutter;
  if (a.splats_per_frame) s << " --splats-per-frame " << *a.splats_per_frame;
  if (const std::string r = restir_flags_text(a.restir); !r.empty()) s << " " << r;
  if (a.equal_time) s << " --equal-time";
  if (a.timing_rounds > 1) s << " --timing-rounds " << a.timing_rounds;
  if (a.save_frames) s << " --save-frames";
  s << " --out " << a.out;
  return s.str();
}

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

std::vector<uint8_t> png(const image::Image& img, float exposure) { return image::encode_png_preview(img, exposure); }

class Evaluation {
 public:
  Evaluation(const EvalArgs& a, EvalClient& client, uint64_t total_steps)
      : a_(a), client_(client), progress_(total_steps, Progress::stderr_is_terminal()) {}

  void scene(const std::string& scene, report::Report& rep) {
    // References first: every method is scored against the same images (refs[f - score_from]).
    std::vector<ReferenceImage> refs;
    for (uint32_t f = a_.score_from; f < a_.frames; ++f) {
      const auto t = Clock::now();
      refs.push_back(client_.reference(scene, f, a_));
      const auto& info = refs.back().info;
      references_.push_back({{"scene", scene}, {"frame", f}, {"spp", info.spp()}, {"relative_error", info.relative_error()},
                             {"relative_error_reached", info.relative_error_reached()}, {"batches", info.batches()},
                             {"cached", info.cached()}, {"cache_key", info.cache_key()}, {"gpu_ms", info.gpu_ms()},
                             {"render_ms", info.render_ms()}, {"disoccluded_mask", !refs.back().mask.empty()}});
      cache_hits_ += info.cached() ? 1 : 0;
      if (a_.save_frames) save_reference(scene, f, refs.back());
      step(f, ms_since(t), info.gpu_ms(), scene + " reference frame " + std::to_string(f) + " spp " + std::to_string(info.spp()) +
                                              (info.cached() ? " (cached)" : ""));
    }

    report::Insets insets;
    insets.scene = scene;
    insets.frame = a_.frames - 1;
    insets.images.emplace_back("reference", png(refs.back().image, a_.exposure));
    std::map<std::string, report::Run> runs;  // the methods' own runs
    for (const auto& method : a_.methods) {
      image::Image last;
      std::vector<float> flip_map;
      runs[method] = run(scene, method, 1, refs, &last, &flip_map);
      insets.images.emplace_back(method, png(last, a_.exposure));
      insets.images.emplace_back("error:" + method, report::error_map_png(flip_map, last.width, last.height, 1.0f));
    }
    // pt's GPU time per sample, from a 1-spp run over the same frames when pt is not a method.
    report::Run pt_timing;
    if (a_.equal_time && !runs.count("pt")) pt_timing = run(scene, "pt", 1, refs);
    std::vector<report::Run*> timed;
    for (const auto& method : a_.methods) timed.push_back(&runs[method]);
    if (!pt_timing.frames.empty()) timed.push_back(&pt_timing);
    time_rounds(scene, timed);
    for (const auto& method : a_.methods) rep.runs.push_back(runs[method]);
    rep.insets.push_back(std::move(insets));
    if (!a_.equal_time) return;

    std::map<uint32_t, report::Run> pt_by_spp;
    pt_by_spp[1] = runs.count("pt") ? runs["pt"] : pt_timing;
    const double pt_ms_per_spp = median_gpu_ms(pt_by_spp[1]);
    pt_ms_per_spp_[scene] = pt_ms_per_spp;
    for (const auto& method : a_.methods) {
      if (method == "pt") continue;
      const report::Run& m = runs[method];
      const uint32_t spp = equal_time_spp(median_gpu_ms(m), pt_ms_per_spp, client_.status().limits().max_spp());
      if (pt_by_spp.count(spp)) {
        step_by(uint64_t(a_.frames) * a_.timing_rounds);  // the same pt run serves again
      } else {
        report::Run pt = run(scene, "pt", spp, refs);
        std::vector<report::Run*> one = {&pt};
        time_rounds(scene, one);
        pt_by_spp[spp] = std::move(pt);
      }
      report::Run pt = pt_by_spp[spp];
      pt.equal_time_pt = true;
      pt.matched_method = method;
      rep.equal_time.push_back(equal_time_entry(m, pt));
      rep.runs.push_back(std::move(pt));
    }
  }

  void finish(report::Report& rep) {
    progress_.finish();
    rep.meta["references"] = references_;
    rep.meta["reference_cache_hits"] = cache_hits_;
    rep.meta["references_rendered"] = references_.size() - cache_hits_;
    rep.meta["pt_ms_per_spp"] = pt_ms_per_spp_;
  }

 private:
  // One round's frame times of a run: its frames' GPU ms and every pass's ms.
  struct RoundTimes {
    std::vector<double> gpu;
    std::map<std::string, std::vector<double>> passes;
    void add(double gpu_ms, const std::map<std::string, double>& pass_ms) {
      gpu.push_back(gpu_ms);
      for (const auto& [pass, ms] : pass_ms) passes[pass].push_back(ms);
    }
    // The round's medians, appended to the run's round_ms and round_pass_ms.
    void append_to(report::Run& run) {
      run.round_ms.push_back(median(std::move(gpu)));
      std::map<std::string, double> per_pass;
      for (auto& [pass, ms] : passes) per_pass[pass] = median(std::move(ms));
      run.round_pass_ms.push_back(std::move(per_pass));
    }
  };

  // --timing-rounds R: R - 1 more rounds of `runs`, each round playing every run's frames
  // interleaved (frame f of each run in turn, EvalClient::run_interleaved), so that a slow stretch
  // of the machine, which on lavapipe moves frame times by up to 30% over a minute, falls on all of
  // them alike. Each run keeps the median frame time of every round (round_ms, the scored run's
  // first; round_pass_ms per pass), and its time is their median. The errors are deterministic for
  // the seed, so the later rounds' frames are timed, not scored.
  void time_rounds(const std::string& scene, const std::vector<report::Run*>& runs) {
    if (a_.timing_rounds <= 1) return;
    for (report::Run* r : runs) {
      RoundTimes scored;
      for (const auto& f : r->frames) scored.add(f.gpu_ms, f.pass_ms);
      scored.append_to(*r);
    }
    std::vector<std::pair<std::string, uint32_t>> plays;
    for (const report::Run* r : runs) plays.emplace_back(r->method, r->spp);
    for (uint32_t round = 1; round < a_.timing_rounds; ++round) {
      std::vector<RoundTimes> times(runs.size());
      auto t = Clock::now();
      client_.run_interleaved(scene, plays, a_, [&](size_t i, MethodImage&& m) {
        if (!m.chosen_method.empty()) runs[i]->round_choices.push_back(m.chosen_method);
        if (m.frame >= a_.score_from) times[i].add(m.gpu_ms, m.pass_ms);
        step(m.frame, ms_since(t), m.gpu_ms,
             scene + " " + plays[i].first + " spp " + std::to_string(plays[i].second) + " frame " + std::to_string(m.frame) + " (timing)");
        t = Clock::now();
      });
      for (size_t i = 0; i < runs.size(); ++i) times[i].append_to(*runs[i]);
    }
  }

  // One method's run over the frames, scored; the last frame's image and HDR-FLIP map when asked.
  report::Run run(const std::string& scene, const std::string& method, uint32_t spp, const std::vector<ReferenceImage>& refs,
                  image::Image* last = nullptr, std::vector<float>* flip_map = nullptr) {
    report::Run r;
    r.scene = scene;
    r.method = method;
    r.spp = spp;
    double cumulative = 0.0;  // over every frame played, warm-up included
    auto t = Clock::now();
    client_.run_method(scene, method, spp, a_, [&](MethodImage&& m) {
      if (!m.chosen_method.empty()) {
        r.round_choices.push_back(m.chosen_method);
        r.choice_reason = m.choice_reason;
      }
      if (m.frame < a_.score_from) {
        cumulative += m.gpu_ms;
        step(m.frame, ms_since(t), m.gpu_ms, scene + " " + method + " spp " + std::to_string(spp) + " frame " + std::to_string(m.frame) + " (warm-up)");
        t = Clock::now();
        return;
      }
      if (a_.save_frames) image::write_exr(frame_path(scene, spp > 1 ? method + "_" + std::to_string(spp) + "spp" : method, m.frame), m.image);
      const bool is_last = m.frame + 1 == a_.frames;
      r.frames.push_back(score_frame(m, refs.at(m.frame - a_.score_from), cumulative, is_last ? flip_map : nullptr));
      cumulative = r.frames.back().cumulative_ms;
      const auto& f = r.frames.back();
      step(m.frame, ms_since(t), m.gpu_ms,
           scene + " " + method + " spp " + std::to_string(spp) + " frame " + std::to_string(m.frame) + " relmse " +
               std::to_string(f.whole.relmse) + " flip " + std::to_string(f.whole.flip));
      if (is_last && last) *last = std::move(m.image);
      t = Clock::now();
    });
    return r;
  }

  // --save-frames: DIR/frames/SCENE/RUN/frame_NNNN.exr, RUN a --methods entry (every character but
  // letters, digits, '.', '=' and '-' written '_'; an equal-time pt run pt_Nspp) or "reference"; a
  // reference with a disocclusion mask carries it as the channel "disoccluded".
  fs::path frame_path(const std::string& scene, std::string run, uint32_t frame) const {
    for (char& c : run)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '=' && c != '-') c = '_';
    if (run.find_first_not_of('.') == std::string::npos) run = "_";
    const fs::path dir = fs::path(a_.out) / "frames" / scene / run;
    fs::create_directories(dir);
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04u.exr", frame);
    return dir / name;
  }
  void save_reference(const std::string& scene, uint32_t frame, const ReferenceImage& ref) const {
    std::vector<image::Channel> extra;
    if (!ref.mask.empty()) extra.push_back({"disoccluded", std::vector<float>(ref.mask.begin(), ref.mask.end())});
    image::write_exr(frame_path(scene, "reference", frame), ref.image, extra);
  }

  void step(uint32_t frame, double wall_ms, double gpu_ms, const std::string& detail) {
    progress_.frame(++done_, frame, wall_ms, gpu_ms, 0, detail);
  }
  void step_by(uint64_t n) { done_ += n; }

  const EvalArgs& a_;
  EvalClient& client_;
  Progress progress_;
  uint64_t done_ = 0;
  nlohmann::json references_ = nlohmann::json::array();
  uint64_t cache_hits_ = 0;
  nlohmann::json pt_ms_per_spp_ = nlohmann::json::object();
};

void print_summary(const report::Report& rep) {
  for (const auto& run : rep.runs) {
    if (run.equal_time_pt) continue;
    const report::Errors e = mean_errors(run);
    std::cout << run.scene << "  " << run.method << "  median " << median_gpu_ms(run) << " ms/frame  relmse " << e.relmse
              << " (luminance " << e.relmse_luminance << ")  mape " << e.mape << "  flip " << e.flip << "\n";
    if (run.round_choices.empty()) continue;
    std::cout << run.scene << "  " << run.method << "  chose";
    for (const auto& c : run.round_choices) std::cout << " " << c;
    const bool mixed = std::any_of(run.round_choices.begin(), run.round_choices.end(),
                                   [&](const std::string& c) { return c != run.round_choices.front(); });
    std::cout << (mixed ? " (the rounds chose differently: its time mixes the choices' times)" : "") << ": "
              << run.choice_reason << "\n";
  }
  for (const auto& et : rep.equal_time)
    std::cout << et.scene << "  equal time: " << et.method << " (" << et.method_median_ms << " ms) vs pt at " << et.pt_spp
              << " spp (" << et.pt_median_ms << " ms): error ratio relmse " << et.ratio.relmse << "  mape " << et.ratio.mape
              << "  flip " << et.ratio.flip << "; relmse ratio at equal ms " << et.relmse_ratio_at_equal_ms << "\n";
}

int run_eval(EvalArgs& a, bool frames_given) {
  a.scenes = split(a.scene_list);
  a.methods = split(a.method_list);
  prepare_eval_frames(a, frames_given);
  const auto start = Clock::now();
  EvalClient client(a.conn, a.timeout_s);
  client.check(a);  // unknown scenes and methods, limits: before any work
  fs::create_directories(a.out);

  report::Report rep;
  rep.meta = {{"server", a.conn.server},
              {"device", client.status().device()},
              {"date", utc_now()},
              {"resolution", {{"width", a.width}, {"height", a.height}}},
              {"frames", a.frames},
              {"score_from", a.score_from},
              {"scenes", a.scenes},
              {"methods", a.methods},
              {"seed", a.seed},
              {"max_depth", a.max_depth},
              {"reference_spp", a.reference_spp},
              {"reference_error", a.reference_error},
              {"equal_time", a.equal_time},
              {"timing_rounds", a.timing_rounds},
              {"camera_path", a.camera_path.empty() ? nlohmann::json() : nlohmann::json(a.camera_path)},
              {"shutter", a.shutter ? nlohmann::json(*a.shutter) : nlohmann::json()},
              {"splats_per_frame", a.splats_per_frame ? nlohmann::json(*a.splats_per_frame) : nlohmann::json()},
              {"restir_options", restir_flags_text(a.restir)},
              {"command_line", command_line(a)}};
  uint64_t non_pt = 0;
  for (const auto& m : a.methods) non_pt += m != "pt";
  const bool has_pt = non_pt < a.methods.size();
  const uint64_t runs_per_scene = a.methods.size() + (a.equal_time ? non_pt + (has_pt ? 0 : 1) : 0);
  const uint64_t per_scene = (a.frames - a.score_from) + a.frames * runs_per_scene * a.timing_rounds;
  Evaluation eval(a, client, per_scene * a.scenes.size());
  std::cerr << "strata: eval of " << a.scenes.size() << " scene(s) x " << a.methods.size() << " method(s), " << a.frames
            << " frame(s) at " << a.width << "x" << a.height << " on " << client.status().device() << " (" << a.conn.server << ")\n";
  for (const auto& scene : a.scenes) eval.scene(scene, rep);
  eval.finish(rep);
  rep.meta["wall_s"] = ms_since(start) / 1000.0;

  const fs::path out(a.out);
  report::write_csv(rep, out / "results.csv");
  report::write_json(rep, out / "results.json");
  report::write_html(rep, out / "report.html");
  print_summary(rep);
  std::cout << "wrote " << (out / "results.csv").string() << ", results.json and report.html ("
            << rep.meta["reference_cache_hits"].get<uint64_t>() << " of " << rep.meta["references"].size()
            << " references from the server's cache)\n";
  return 0;
}

}  // namespace

Runner add_eval_command(CLI::App& app) {
  auto a = std::make_shared<EvalArgs>();
  auto* cmd = app.add_subcommand("eval", "error against run time: methods vs converged references; results.csv/json, report.html");
  add_connection_flags(cmd, a->conn);
  cmd->add_option("--scenes", a->scene_list, "scenes, comma-separated (the server's ListScenes)")->capture_default_str();
  cmd->add_option("--methods", a->method_list,
                  "methods, comma-separated (the server's status lists those available); an entry may give ReSTIR flags of its "
                  "own, NAME[:FLAG=VALUE]... (e.g. restir-splat:disocclusion-initial-candidates=8), over those given to all")
      ->capture_default_str();
  auto* frames = cmd->add_option("--frames", a->frames, "frames of each scene's default animation (not with --camera-path)")
                     ->capture_default_str();
  cmd->add_option("--score-from", a->score_from,
                  "warm-up: frames 0..N-1 are played by every method but neither scored nor timed (no references for them); "
                  "a method that learns over frames (restir-multilayer's active domains) is then scored in its steady state")
      ->capture_default_str();
  cmd->add_option("--camera-path", a->camera_path,
                  "JSON {\"frames\": [FrameInput, ...]} as for strata stream, replacing the default animation: each entry sets "
                  "animation_frame and may set camera, transforms and lod_changes; its entries are the frames (--frames "
                  "must not be given)");
  auto* shutter = cmd->add_option("--shutter", a->shutter_value,
                                  "camera.shutter of every frame, 0..1 (motion blur); > 0 needs --camera-path whose entries "
                                  "all set camera");
  auto* splats = cmd->add_option("--splats-per-frame", a->splats_value,
                                 "RenderOptions.splats_per_frame of the methods' sessions, 1..64 (restir-splat*: K splats "
                                 "over the shutter; default: the server's)");
  add_restir_flags(cmd, a->restir, /*eval=*/true);
  cmd->add_option("--width", a->width, "image width")->capture_default_str();
  cmd->add_option("--height", a->height, "image height")->capture_default_str();
  cmd->add_option("--reference-spp", a->reference_spp, "samples per pixel of each reference")->capture_default_str();
  cmd->add_option("--reference-error", a->reference_error,
                  "stop a reference early at this estimated relative standard error (0: never)")
      ->capture_default_str();
  cmd->add_option("--seed", a->seed, "random seed of the methods (references derive theirs from it)")->capture_default_str();
  cmd->add_option("--max-depth", a->max_depth, "path segments (default: the server's)");
  cmd->add_flag("--equal-time", a->equal_time, "also run pt with as many spp as fit in each method's median frame time");
  cmd->add_option("--timing-rounds", a->timing_rounds,
                  "rounds of every method (and equal-time pt run): the scored run, then R - 1 rounds that play the "
                  "runs' frames interleaved, one frame of each in turn; a run's time is the median of its rounds' median "
                  "frame times (1..16)")
      ->check(CLI::Range(1u, 16u))
      ->capture_default_str();
  cmd->add_option("--exposure", a->exposure, "exposure of the PNG insets in stops")->capture_default_str();
  cmd->add_flag("--save-frames", a->save_frames,
                "also write every scored frame of every run, and its reference (with the disocclusion mask as the "
                "channel 'disoccluded'), as EXR under OUT/frames/SCENE/RUN/");
  cmd->add_option("--out", a->out, "output directory")->capture_default_str();
  cmd->add_option("--timeout", a->timeout_s, "seconds for each call (a reference can take long)")->capture_default_str();
  return [a, frames, shutter, splats] {
    if (shutter->count() > 0) a->shutter = a->shutter_value;
    if (splats->count() > 0) a->splats_per_frame = a->splats_value;
    return run_eval(*a, frames->count() > 0);
  };
}

}  // namespace strata::client
