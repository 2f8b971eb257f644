#pragma once
// The RPCs of `strata eval`: the server's status, scenes and methods (checked before any work),
// references of exact frame states (RenderReference), and lockstep streams of a method over the
// frames (a scene's default animation or a camera path, eval_frames.h), with every frame's HDR
// image and per-pass GPU times.
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "connection_options.h"
#include "image/image.h"
#include "restir_flags.h"
#include "strata/v1/render.grpc.pb.h"

namespace strata::client {

namespace v1 = ::strata::v1;

struct EvalSettings {
  ConnectionOptions conn;          // --server, TLS, token
  std::vector<std::string> scenes{"cornell"}, methods{"pt", "restir-gather"};
  uint32_t frames = 16, width = 256, height = 256, seed = 0;
  uint32_t score_from = 0;         // frames before it are played (warm-up), neither scored nor timed
  uint32_t max_depth = 0;          // 0: the server's default
  uint32_t reference_spp = 1024;
  float reference_error = 0.0f;    // 0: no early stop
  bool equal_time = false;
  uint32_t timing_rounds = 1;      // rounds of each method (the scored run, then interleaved ones) whose median frame times are its time
  std::string camera_path;         // empty: each scene's default animation
  std::vector<v1::FrameInput> path;  // its entries, one per frame (eval_frames.h)
  std::optional<float> shutter;    // --shutter: every entry's camera.shutter
  std::optional<uint32_t> splats_per_frame;  // the sessions' RenderOptions.splats_per_frame (unset: the server's)
  RestirFlags restir;              // the methods' ReSTIR options, those given (pt reports them as not applying)
  std::string out = "out/eval";
  double timeout_s = 3600.0;       // per RPC (a reference may take long on lavapipe)
};

// A scene's reference of one frame.
struct ReferenceImage {
  image::Image image;
  std::vector<uint8_t> mask;       // disoccluded pixels (width*height), empty when unknown
  v1::Reference info;              // what the server said, image and mask bytes removed
};

// One frame a method rendered.
struct MethodImage {
  uint32_t frame = 0;
  image::Image image;
  double gpu_ms = 0.0;
  std::map<std::string, double> pass_ms;
  // Where method auto chose on this frame (its `method` entry in option_changes): what, and why.
  std::string chosen_method, choice_reason;
};

// A frame's image as the server encoded it (EXR_HALF or RAW_RGBA16F).
image::Image decode_image(const v1::Image& img);

class EvalClient {
 public:
  // Connects and reads the server's status (its limits size the channel for frames). Every call
  // of one EvalClient carries the same x-strata-session, so that behind a session-affine proxy
  // the references and the sessions of a run are on one daemon.
  EvalClient(const ConnectionOptions& conn, double timeout_s);

  const v1::ServerStatus& status() const { return status_; }
  const std::string& address() const { return address_; }

  // Throws std::runtime_error naming every unknown scene or unavailable method, with the lists
  // the server offers, and settings over the server's limits.
  void check(const EvalSettings& s);

  // The reference of `frame` (eval_frame_state), with the previous frame's state for frames > 0
  // (for the disoccluded mask, and where an open shutter opens).
  ReferenceImage reference(const std::string& scene, uint32_t frame, const EvalSettings& s);

  // Creates a session of `method` with `spp`, streams frames 0..frames-1 (eval_frame_input) in
  // lockstep (RAW_RGBA16F) and hands each frame to `on_frame`, then deletes the session.
  void run_method(const std::string& scene, const std::string& method, uint32_t spp, const EvalSettings& s,
                  const std::function<void(MethodImage&&)>& on_frame);

  // A session for each (method, spp) of `runs`, all open at once, played frame by frame in turn:
  // frame f of every run before frame f + 1 of any, one frame rendering at a time. A slow stretch
  // of the machine then falls on every run alike (the timing rounds). More runs than the server's
  // max_sessions play in groups of that many. `on_frame` gets the run's index.
  void run_interleaved(const std::string& scene, const std::vector<std::pair<std::string, uint32_t>>& runs,
                       const EvalSettings& s, const std::function<void(size_t, MethodImage&&)>& on_frame);

 private:
  v1::SceneSource scene_source(const std::string& scene) const;
  std::chrono::milliseconds timeout() const;
  // Before a method's first timed or scored run on a scene: waits until the daemon renders it with
  // its own pipelines, not its progressive start's stand-in (eval_session.h, wait_until_compiled).
  void ensure_compiled(const std::string& scene, const std::string& method, const EvalSettings& s);
  std::set<std::string> compiled_;  // "scene|method" pairs ensure_compiled has seen through

  std::string address_;
  double timeout_s_;
  std::unique_ptr<v1::RenderService::Stub> stub_;
  v1::ServerStatus status_;
  std::map<std::string, v1::SceneEntry::Kind> scenes_;  // from ListScenes
};

}  // namespace strata::client
