#pragma once
// A session (sessions/{session}): its scene, method and options, the frame state that inputs
// change, and the Renderer holding its GPU state. The Renderer is created with the session,
// released when a stream ends, and re-created (history reset) by the next frame.
//
// Progressive start (`stratad serve`; a Session given a compiler): a session whose method is not pt
// and not auto, and whose pipelines are not listed as compiled in Mesa's cache, submits its renderer's exact pipelines to the compiler at creation, and until they
// are compiled its frames are rendered by pt at the same settings (lavapipe compiles pt's in about
// a second, restir-gather's in about a minute and a half of CPU). Each such frame says so in its
// pass decisions (a first entry named after the method, ran = false); the frame after the compile
// ends renders the method, with a history reset whose reason says why (its history starts there).
// Without a compiler (tests, `stratad render`, eval) every frame is the method's.
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <grpcpp/support/status.h>

#include "gpu/context.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "service/config.h"
#include "service/frame_input.h"
#include "service/auto_calibration.h"
#include "service/metrics.h"
#include "service/method_auto.h"
#include "service/options.h"
#include "service/session_spec.h"
#include "service/warm_up.h"
#include "strata/v1/render.pb.h"

namespace strata::service {

// One rendered frame on its way to the client.
struct RenderedFrame {
  render::FrameResult result;
  uint64_t frame_index = 0;
  uint64_t input_sequence = 0;
  uint64_t coalesced = 0;  // inputs merged into the one rendered (and into frames dropped before it)
  uint64_t dropped_before = 0;  // frames of this stream dropped since the previous one was sent
  bool history_reset = false;
  std::string history_reset_reason;
  std::vector<v1::Decision> option_changes;  // Frame.option_changes
  double queued_ms = 0.0, render_ms = 0.0;
  std::vector<v1::ImageEncoding> encodings;
  float exposure = 0.0f;
  GaugeHold held;  // this frame's bytes on ServiceMetrics::buffered_frame_bytes
};

// The stream attached to a session, as the session and the registry see it.
class AttachedStream {
 public:
  virtual ~AttachedStream() = default;
  // Ends the stream with `status` as soon as no write is in flight (deleted, expired).
  virtual void end(grpc::Status status) = 0;
  // Finishes the frames whose input already arrived, then ends the stream with `status`.
  virtual void drain(grpc::Status status) = 0;
  // Cancels the call when an end requested earlier has not completed by `now` (a client that does
  // not read can hold a write open forever).
  virtual void enforce_end_deadline(std::chrono::steady_clock::time_point now) = 0;
};

class Session {
 public:
  using Clock = std::chrono::steady_clock;

  // `progressive`: the compiler of a progressive start (null: none).
  Session(std::string name, std::shared_ptr<const scene::Scene> scene, SessionSpec spec, const gpu::Context& ctx,
          ServiceMetrics& metrics, WarmUp* progressive = nullptr);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  const std::string& name() const { return name_; }
  const scene::Scene& scene() const { return *scene_; }
  // The method in use (for `method auto`: restir-gather while it calibrates, then its choice).
  const render::MethodSpec& method() const;
  // The client asked for `method auto` (by name or by naming no method).
  bool auto_method() const { return spec_.auto_method; }
  // The row a FrameInput's options are checked against: the method's; for auto restir-gather's,
  // which it may choose again when it calibrates again.
  const render::MethodSpec& checked_method() const;
  v1::Session describe(const ServiceConfig& config) const;

  // One stream at a time: false when another one is attached.
  bool attach(const std::shared_ptr<AttachedStream>& stream);
  // Detaches `stream` if it is the one attached; true when it was.
  bool detach(const AttachedStream* stream);
  std::shared_ptr<AttachedStream> stream() const;

  void note_input(uint64_t sequence);
  void note_dropped(uint64_t frames);
  void touch();
  // While no stream is attached: since when the session is idle.
  std::optional<Clock::time_point> idle_since() const;

  // Applies `input` and renders one frame (re-creating the GPU state when it was released or the
  // resolution or a renderer setting changed). Throws on device errors.
  RenderedFrame render(PendingInput input);
  // Frees the GPU state (device memory) unless a stream is attached; the next render re-creates it.
  void release_gpu();
  uint64_t device_bytes() const;

 private:
  void create_renderer_locked();  // render_mu_ held
  // Progressive start (render_mu_ held): submits the compile of settings_'s pipelines.
  void submit_compile_locked();
  // Progressive start (render_mu_ held): whether frames are still rendered by pt; the frame after
  // the first stage of the compile adds to `reason` that the method takes over, and history_held_
  // says whether its history passes still wait for the second (service/warm_up.h).
  bool compiling_locked(uint64_t index, std::string& reason);
  void apply_locked(const PendingInput& input, std::string& reset_reason, std::vector<v1::Decision>& option_changes);
  // `method auto` (render_mu_ held): drops the choice so that the next frame calibrates again.
  void recalibrate_locked(const std::string& why);
  // Renders frame `index` with the calibration (starting it when there is none) and, after its last
  // frame, makes its choice the session's method; a `method` entry in `option_changes` says so.
  render::FrameResult render_calibrating_locked(uint64_t index, std::vector<v1::Decision>& option_changes);
  void redecide_locked();  // mu_ held: decisions_ from spec_ (and auto's state)

  const std::string name_;
  const std::shared_ptr<const scene::Scene> scene_;
  const gpu::Context& ctx_;
  ServiceMetrics& metrics_;
  const v1::SceneAnalysis analysis_;
  // `layers auto` as measured for the session's resolution (the `layers` decision's figure).
  std::optional<render::LayerCount> measured_layers_;
  uint32_t measured_width_ = 0, measured_height_ = 0;
  const std::optional<render::LayerCount>& measured_layers(const v1::RenderOptions& options, uint32_t width, uint32_t height);
  const Clock::time_point created_steady_;
  const std::chrono::system_clock::time_point created_;

  // Rendering (scheduler thread, and release_gpu): guarded by render_mu_.
  std::mutex render_mu_;
  std::unique_ptr<render::Renderer> renderer_;
  scene::FrameState frame_state_;
  std::optional<scene::Camera> last_camera_;  // of the frame rendered last (where its shutter closed)
  render::RenderSettings settings_;
  // `method auto`: the calibration in progress, if any (none once it has chosen).
  std::unique_ptr<AutoCalibration> calibration_;
  // Progressive start: the compiler, the compile of the method's pipelines while it runs, and the
  // pt renderer of the frames meanwhile.
  WarmUp* const progressive_;
  std::shared_ptr<const PipelineCompile> compile_;
  std::unique_ptr<render::Renderer> stand_in_;
  bool history_held_ = false;  // the method renders, its history passes held until compiled
  Clock::time_point stand_in_resume_{};  // the stand-in's next frame starts no sooner (k_stand_in_idle)

  // Description and counters: guarded by mu_ (taken after render_mu_ when both are needed).
  mutable std::mutex mu_;
  SessionSpec spec_;
  std::vector<v1::Decision> decisions_;
  // `method auto`: what its calibration measured at the session's resolution (none before its first
  // frame; its method is null until it has chosen), the frame the calibration starts or started at,
  // and why it calibrates.
  std::optional<AutoChoice> auto_choice_;
  uint64_t calibration_start_ = 0;
  std::string calibration_reason_ = "the session's first frames";
  std::map<std::string, uint64_t> memory_;
  std::vector<render::PassDecision> last_passes_;
  std::weak_ptr<AttachedStream> stream_;
  bool attached_ = false;
  Clock::time_point idle_since_;
  uint64_t frames_rendered_ = 0, frames_dropped_ = 0, inputs_coalesced_ = 0, last_input_ = 0;
  bool released_ = false;
};

}  // namespace strata::service
