#include "service/reference_service.h"

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <optional>

#include "image/image.h"
#include "render/disocclusion.h"
#include "render/reference.h"
#include "scene/shutter.h"
#include "service/errors.h"
#include "service/frame_input.h"
#include "service/input_checks.h"
#include "service/scene_source.h"

namespace strata::service {
namespace {

using Clock = std::chrono::steady_clock;
constexpr size_t k_cached_builtins = 4;
constexpr uint32_t k_default_max_depth = 16;
constexpr auto k_poll = std::chrono::milliseconds(50);

// One reference's accumulation on the frame scheduler: a batch per turn, then it queues itself
// again behind the sessions waiting for frames, until done or cancelled. With a previous frame
// state it then computes the disocclusion mask (one more turn); a cached reference runs only that.
class ReferenceJob final : public ScheduledStream, public std::enable_shared_from_this<ReferenceJob> {
 public:
  struct MaskRequest {
    scene::FrameState previous, frame;
    uint32_t width = 0, height = 0;
  };
  // `render` (null when the image came from the cache) draws `scene`, which the job keeps alive.
  ReferenceJob(const gpu::Context& ctx, FrameScheduler& scheduler, std::shared_ptr<const scene::Scene> scene,
               std::unique_ptr<render::ReferenceRender> render, std::optional<MaskRequest> mask)
      : ctx_(ctx), scheduler_(scheduler), scene_(std::move(scene)), render_(std::move(render)), mask_request_(std::move(mask)) {}

  void render_pending() override {
    if (cancelled_.load()) return finish(grpc::Status(grpc::StatusCode::CANCELLED, "cancelled"));
    if (render_ && !render_->done()) {
      grpc::Status st = guarded([&] { render_->render_batch(); });
      if (!st.ok()) return finish(std::move(st));
      if (!render_->done() || mask_request_) return scheduler_.enqueue(shared_from_this());
      return finish(grpc::Status::OK);
    }
    if (mask_request_) {
      const MaskRequest& m = *mask_request_;
      grpc::Status st = guarded([&] { mask_ = render::DisocclusionMask(ctx_, *scene_).compute(m.previous, m.frame, m.width, m.height); });
      return finish(std::move(st));
    }
    finish(grpc::Status::OK);
  }

  // True once finished (status() is then valid).
  bool wait_for(std::chrono::milliseconds timeout) {
    std::unique_lock lock(mu_);
    return cv_.wait_for(lock, timeout, [&] { return finished_; });
  }
  grpc::Status status() const {
    std::lock_guard lock(mu_);
    return status_;
  }
  // The accumulation stops before its next batch.
  void cancel() { cancelled_ = true; }
  render::ReferenceEntry result() const { return render_->result(); }
  const std::vector<uint8_t>& mask() const { return mask_; }

 private:
  void finish(grpc::Status st) {
    {
      std::lock_guard lock(mu_);
      finished_ = true;
      status_ = std::move(st);
    }
    cv_.notify_all();
  }

  const gpu::Context& ctx_;
  FrameScheduler& scheduler_;
  std::shared_ptr<const scene::Scene> scene_;
  std::unique_ptr<render::ReferenceRender> render_;
  std::optional<MaskRequest> mask_request_;
  std::vector<uint8_t> mask_;
  std::atomic<bool> cancelled_{false};
  mutable std::mutex mu_;
  std::condition_variable cv_;
  bool finished_ = false;
  grpc::Status status_;
};

// Counts a request in flight for as long as it lives.
struct InFlight {
  explicit InFlight(std::atomic<uint32_t>& n) : count(n), value(n.fetch_add(1) + 1) {}
  ~InFlight() { count.fetch_sub(1); }
  std::atomic<uint32_t>& count;
  uint32_t value;
};

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// Where the shutter of `camera` opened (motion blur, RS-main 4.4): on the way from the previous
// frame's camera, which an open shutter therefore needs.
std::optional<scene::Camera> open_shutter(const scene::Camera& camera, const std::optional<scene::FrameState>& previous) {
  if (!(camera.shutter > 0.0f)) return std::nullopt;
  if (!previous)
    fail_invalid("previous_frame is required when frame.camera.shutter = " + format_float(camera.shutter) +
                 " > 0: the shutter opens on the way from the previous frame's camera (motion blur)");
  return scene::shutter_open_camera(previous->camera, camera);
}

std::filesystem::path cache_dir(const ServiceConfig& config) {
  return config.reference_cache.empty() ? render::ReferenceCache::default_dir() : config.reference_cache;
}

}  // namespace

scene::FrameState resolve_frame_state(const v1::FrameState& state, const scene::Scene& scene, const ServiceLimits& limits,
                                      const std::string& field) {
  // The checks of a FrameInput (camera, transforms, LoD levels), with the field names under `field`.
  v1::FrameInput in;
  in.set_animation_frame(state.animation_frame());
  if (state.has_camera()) *in.mutable_camera() = state.camera();
  *in.mutable_transforms() = state.transforms();
  *in.mutable_lod_changes() = state.lod_changes();
  *in.mutable_light_transforms() = state.light_transforms();
  PendingInput p;
  try {
    p = parse_frame_input(in, scene, limits);
  } catch (const ServiceError& e) {
    throw ServiceError(e.code, field + "." + e.what());
  }
  scene::FrameState out = scene.frame_state(state.animation_frame());
  if (p.camera) out.camera = *p.camera;
  for (const auto& [id, m] : p.transforms) out.transforms.at(id) = m;
  for (const auto& [id, level] : p.lods) out.lods.at(id) = level;
  for (const auto& [id, m] : p.lights) out.lights.at(id) = m;
  return out;
}

ReferenceService::ReferenceService(ServiceCore& core) : core_(core), cache_(cache_dir(core.config)) {}

ReferenceService::~ReferenceService() = default;

ReferenceService::LoadedScene ReferenceService::load_scene(const v1::SceneSource& source) {
  // Built-in scenes are generated (LoDs included) and hashed once; files and inline bytes every time.
  const bool builtin = source.source_case() == v1::SceneSource::kBuiltin;
  if (builtin) {
    std::lock_guard lock(mu_);
    for (auto it = builtins_.begin(); it != builtins_.end(); ++it)
      if (it->first == source.builtin()) {
        builtins_.splice(builtins_.begin(), builtins_, it);
        return builtins_.front().second;
      }
  }
  LoadedScene s;
  s.scene = load_scene_source(source, core_.config);
  s.hash = render::scene_content_hash(*s.scene);
  if (builtin) {
    std::lock_guard lock(mu_);
    builtins_.emplace_front(source.builtin(), s);
    if (builtins_.size() > k_cached_builtins) builtins_.pop_back();
  }
  return s;
}

void ReferenceService::respond(const v1::ReferenceRequest& req, const render::ReferenceEntry& e, v1::Reference* resp) const {
  const auto start = Clock::now();
  const bool raw = req.encoding() == v1::IMAGE_ENCODING_RAW_RGBA16F;
  const std::vector<uint8_t> bytes = raw ? image::encode_rgba16f(e.image) : image::encode_exr(e.image);
  auto* img = resp->mutable_image();
  img->set_encoding(raw ? v1::IMAGE_ENCODING_RAW_RGBA16F : v1::IMAGE_ENCODING_EXR_HALF);
  img->set_width(e.image.width);
  img->set_height(e.image.height);
  img->set_data(std::string(bytes.begin(), bytes.end()));
  img->set_encode_ms(ms_since(start));
  resp->set_spp(e.spp);
  resp->set_relative_error(e.relative_error);
  resp->set_relative_error_reached(e.relative_error_reached);
  resp->set_batches(e.batches);
  resp->set_gpu_ms(e.gpu_ms);
}

grpc::Status ReferenceService::render(grpc::ServerContext* ctx, const v1::ReferenceRequest& req, v1::Reference* resp) {
  const auto start = Clock::now();
  return guarded([&] {
    if (core_.draining.load()) fail(grpc::StatusCode::UNAVAILABLE, "stratad is draining (shutting down): no new references");
    const ServiceLimits& limits = core_.config.limits;
    // The request's own fields first, the scene-dependent ones once the scene is loaded.
    if (!req.has_scene()) fail_invalid("scene is required: set scene.builtin, scene.path or scene.glb");
    if (!req.has_resolution()) fail_invalid("resolution is required (width and height in pixels)");
    check_resolution(req.resolution(), limits, "resolution");
    if (!req.has_frame()) fail_invalid("frame is required: the frame state to render (frame.animation_frame, camera, transforms, lod_changes)");
    if (req.spp() < 1 || req.spp() > limits.max_reference_spp)
      fail_invalid("spp = " + std::to_string(req.spp()) + " is outside [1, " + std::to_string(limits.max_reference_spp) +
                   "] (max_reference_spp)");
    if (req.max_depth() > limits.max_depth)
      fail_invalid("max_depth = " + std::to_string(req.max_depth()) + " is outside [1, " + std::to_string(limits.max_depth) +
                   "] (max_depth; 0 = the default, " + std::to_string(k_default_max_depth) + ")");
    const float target = req.relative_error();
    if (!std::isfinite(target) || target < 0.0f || target >= 1.0f)
      fail_invalid("relative_error = " + format_float(target) + " is outside [0, 1) (0 = no early stop)");
    const int enc = req.encoding();
    if (enc != v1::IMAGE_ENCODING_UNSPECIFIED && enc != v1::IMAGE_ENCODING_EXR_HALF && enc != v1::IMAGE_ENCODING_RAW_RGBA16F)
      fail_invalid("encoding = " + (v1::ImageEncoding_IsValid(enc) ? encoding_name(v1::ImageEncoding(enc)) : std::to_string(enc)) +
                   " is not an HDR encoding: use EXR_HALF or RAW_RGBA16F");
    const InFlight in_flight(in_flight_);
    if (in_flight.value > limits.max_sessions)
      fail(grpc::StatusCode::RESOURCE_EXHAUSTED, std::to_string(in_flight.value - 1) +
                                                     " references are being rendered; at most max_sessions = " +
                                                     std::to_string(limits.max_sessions) + " at once");

    const LoadedScene loaded = load_scene(req.scene());
    const scene::Scene& sc = *loaded.scene;
    render::ReferenceKey key;
    key.scene_hash = loaded.hash;
    key.frame = resolve_frame_state(req.frame(), sc, limits, "frame");
    std::optional<scene::FrameState> previous;
    if (req.has_previous_frame()) previous = resolve_frame_state(req.previous_frame(), sc, limits, "previous_frame");
    key.frame.camera_open = open_shutter(key.frame.camera, previous);
    std::optional<ReferenceJob::MaskRequest> mask;
    if (previous)
      mask = ReferenceJob::MaskRequest{*previous, key.frame, req.resolution().width(), req.resolution().height()};
    key.width = req.resolution().width();
    key.height = req.resolution().height();
    key.max_depth = req.max_depth() ? std::min(req.max_depth(), limits.max_depth) : std::min(k_default_max_depth, limits.max_depth);
    key.seed = req.seed();
    key.spp = req.spp();
    key.relative_error = target;
    const std::string cache_key = render::reference_cache_key(key);
    resp->set_cache_key(cache_key);
    resp->set_scene(sc.name);

    // Runs a job on the frame scheduler and waits for it, cancelling it if the client goes away
    // or the server drains.
    auto run = [&](const std::shared_ptr<ReferenceJob>& job, const char* what) {
      core_.scheduler.enqueue(job);
      while (!job->wait_for(k_poll)) {
        if (ctx && ctx->IsCancelled()) {
          job->cancel();
          fail(grpc::StatusCode::CANCELLED, "the client cancelled RenderReference");
        }
        if (core_.draining.load()) {
          job->cancel();
          fail(grpc::StatusCode::UNAVAILABLE, std::string("stratad is draining (shutting down): ") + what + " was not finished");
        }
      }
      const grpc::Status st = job->status();
      if (!st.ok()) throw ServiceError(st.error_code(), std::string(what) + ": " + st.error_message());
    };

    std::string why;
    if (auto entry = cache_.load(cache_key, &why)) {
      resp->set_cached(true);
      respond(req, *entry, resp);
      if (mask) {
        auto job = std::make_shared<ReferenceJob>(core_.ctx, core_.scheduler, loaded.scene, nullptr, mask);
        run(job, "the disocclusion mask");
        resp->set_disoccluded_mask(std::string(job->mask().begin(), job->mask().end()));
      }
      resp->set_render_ms(ms_since(start));
      return;
    }
    if (!why.empty()) std::fprintf(stderr, "stratad: reference cache: %s; rendering it again\n", why.c_str());

    render::ReferenceSettings settings;
    settings.width = key.width;
    settings.height = key.height;
    settings.max_depth = key.max_depth;
    settings.seed = key.seed;
    settings.spp = key.spp;
    settings.relative_error = target;
    auto job = std::make_shared<ReferenceJob>(core_.ctx, core_.scheduler, loaded.scene,
                                              std::make_unique<render::ReferenceRender>(core_.ctx, sc, key.frame, settings), mask);
    run(job, "rendering the reference");
    const render::ReferenceEntry entry = job->result();
    try {
      cache_.store(cache_key, entry);
    } catch (const std::exception& e) {  // the reference is still good; only the cache misses it
      std::fprintf(stderr, "stratad: reference cache: %s\n", e.what());
    }
    resp->set_cached(false);
    respond(req, entry, resp);
    if (mask) resp->set_disoccluded_mask(std::string(job->mask().begin(), job->mask().end()));
    resp->set_render_ms(ms_since(start));
  });
}

}  // namespace strata::service
