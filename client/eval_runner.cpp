#include "eval_runner.h"

#include <algorithm>
#include <span>
#include <stdexcept>

#include "connection.h"
#include "eval_frames.h"
#include "eval_method.h"
#include "eval_session.h"

namespace strata::client {
namespace {

constexpr uint32_t k_max_splats_per_frame = 64;  // the range of RenderOptions.splats_per_frame (render.proto)

std::string joined(const std::vector<std::string>& items) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : ", ") + i;
  return s;
}

}  // namespace

image::Image decode_image(const v1::Image& img) {
  const auto& d = img.data();
  const std::span<const uint8_t> bytes(reinterpret_cast<const uint8_t*>(d.data()), d.size());
  if (img.encoding() == v1::IMAGE_ENCODING_EXR_HALF) return image::decode_exr(bytes);
  if (img.encoding() == v1::IMAGE_ENCODING_RAW_RGBA16F) return image::decode_rgba16f(bytes, img.width(), img.height());
  throw std::runtime_error("the server sent an image in encoding " + std::to_string(int(img.encoding())) +
                           ", not EXR_HALF or RAW_RGBA16F");
}

EvalClient::EvalClient(const ConnectionOptions& conn, double timeout_s) : address_(conn.server), timeout_s_(timeout_s) {
  const std::string affinity = new_session_id();
  auto stub = v1::RenderService::NewStub(open_channel(conn, affinity));
  {
    grpc::ClientContext ctx;
    set_deadline(ctx, std::chrono::seconds(30));
    auto st = stub->GetServerStatus(&ctx, {}, &status_);
    if (!st.ok()) throw RpcError("GetServerStatus (" + address_ + ")", st);
  }
  // Frames and references are at most limits.max_frame_bytes.
  stub_ = v1::RenderService::NewStub(open_channel(conn, affinity, std::max<uint64_t>(status_.limits().max_frame_bytes(), 4u << 20)));
  grpc::ClientContext ctx;
  set_deadline(ctx, std::chrono::seconds(30));
  v1::ListScenesResponse scenes;
  auto st = stub_->ListScenes(&ctx, {}, &scenes);
  if (!st.ok()) throw RpcError("ListScenes", st);
  for (const auto& e : scenes.scenes()) scenes_[e.name()] = e.kind();
}

std::chrono::milliseconds EvalClient::timeout() const { return std::chrono::milliseconds(int64_t(timeout_s_ * 1000.0)); }

void EvalClient::check(const EvalSettings& s) {
  if (s.scenes.empty()) throw std::runtime_error("--scenes is empty");
  if (s.methods.empty()) throw std::runtime_error("--methods is empty");
  if (s.frames < 1) throw std::runtime_error("--frames must be at least 1");
  if (s.score_from >= s.frames)
    throw std::runtime_error("--score-from = " + std::to_string(s.score_from) + " leaves no frame to score: it must be below the " +
                             std::to_string(s.frames) + " frames played");
  std::vector<std::string> names;
  for (const auto& [name, kind] : scenes_) names.push_back(name);
  for (const auto& scene : s.scenes)
    if (!scenes_.count(scene))
      throw std::runtime_error("--scenes: '" + scene + "' is not a scene of " + address_ + "; its scenes: " + joined(names));
  const std::vector<std::string> methods(status_.methods().begin(), status_.methods().end());
  for (const auto& entry : s.methods) {
    const std::string m = parse_eval_method(entry, s.restir).method;  // and its flags: checked here, before any work
    if (std::find(methods.begin(), methods.end(), m) == methods.end())
      throw std::runtime_error("--methods: '" + m + "' is not available on " + address_ + "; available: " + joined(methods));
  }
  for (size_t i = 0; i < s.methods.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (s.methods[i] == s.methods[j]) throw std::runtime_error("--methods: '" + s.methods[i] + "' is given twice");
  const auto& l = status_.limits();
  if (s.width < 1 || s.height < 1 || s.width > l.max_dimension() || s.height > l.max_dimension() ||
      uint64_t(s.width) * s.height > l.max_pixels())
    throw std::runtime_error("--width x --height = " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                             " is over the server's limits (max_dimension " + std::to_string(l.max_dimension()) +
                             ", max_pixels " + std::to_string(l.max_pixels()) + ")");
  if (s.reference_spp < 1 || s.reference_spp > l.max_reference_spp())
    throw std::runtime_error("--reference-spp = " + std::to_string(s.reference_spp) + " is outside [1, " +
                             std::to_string(l.max_reference_spp()) + "] (the server's max_reference_spp)");
  if (!(s.reference_error >= 0.0f && s.reference_error < 1.0f))
    throw std::runtime_error("--reference-error must be in [0, 1) (0: no early stop)");
  if (s.max_depth > l.max_depth())
    throw std::runtime_error("--max-depth = " + std::to_string(s.max_depth) + " is over the server's max_depth " +
                             std::to_string(l.max_depth()));
  if (s.splats_per_frame && (*s.splats_per_frame < 1 || *s.splats_per_frame > k_max_splats_per_frame))
    throw std::runtime_error("--splats-per-frame = " + std::to_string(*s.splats_per_frame) + " is outside [1, " +
                             std::to_string(k_max_splats_per_frame) + "] (RenderOptions.splats_per_frame)");
}

v1::SceneSource EvalClient::scene_source(const std::string& scene) const {
  v1::SceneSource src;
  auto it = scenes_.find(scene);
  if (it != scenes_.end() && it->second == v1::SceneEntry::FILE) src.set_path(scene);
  else src.set_builtin(scene);
  return src;
}

ReferenceImage EvalClient::reference(const std::string& scene, uint32_t frame, const EvalSettings& s) {
  v1::ReferenceRequest req;
  *req.mutable_scene() = scene_source(scene);
  req.mutable_resolution()->set_width(s.width);
  req.mutable_resolution()->set_height(s.height);
  *req.mutable_frame() = eval_frame_state(s, frame);
  if (frame > 0) *req.mutable_previous_frame() = eval_frame_state(s, frame - 1);
  req.set_max_depth(s.max_depth);
  req.set_seed(s.seed);
  req.set_spp(s.reference_spp);
  req.set_relative_error(s.reference_error);
  req.set_encoding(v1::IMAGE_ENCODING_RAW_RGBA16F);
  grpc::ClientContext ctx;
  set_deadline(ctx, timeout());
  ReferenceImage out;
  auto st = stub_->RenderReference(&ctx, req, &out.info);
  if (!st.ok()) throw RpcError("RenderReference (" + scene + " frame " + std::to_string(frame) + ")", st);
  out.image = decode_image(out.info.image());
  const auto& mask = out.info.disoccluded_mask();
  if (!mask.empty()) {
    if (mask.size() != size_t(s.width) * s.height)
      throw std::runtime_error("RenderReference: disoccluded_mask has " + std::to_string(mask.size()) + " bytes for " +
                               std::to_string(s.width) + "x" + std::to_string(s.height) + " pixels");
    out.mask.assign(mask.begin(), mask.end());
  }
  out.info.clear_image();
  out.info.clear_disoccluded_mask();
  return out;
}

void EvalClient::ensure_compiled(const std::string& scene, const std::string& method, const EvalSettings& s) {
  if (!compiled_.insert(scene + "|" + method).second) return;
  wait_until_compiled(*stub_, scene_source(scene), scene, method, s, timeout());
}

void EvalClient::run_method(const std::string& scene, const std::string& method, uint32_t spp, const EvalSettings& s,
                            const std::function<void(MethodImage&&)>& on_frame) {
  ensure_compiled(scene, method, s);
  EvalSession session(*stub_, scene_source(scene), scene, method, spp, s, timeout());
  for (uint32_t f = 0; f < s.frames; ++f) on_frame(session.next(f));
  session.finish();
}

void EvalClient::run_interleaved(const std::string& scene, const std::vector<std::pair<std::string, uint32_t>>& runs,
                                 const EvalSettings& s, const std::function<void(size_t, MethodImage&&)>& on_frame) {
  // At most the server's max_sessions at once: more runs play in groups, each interleaved.
  const size_t group = std::max<size_t>(1, status_.limits().max_sessions());
  for (const auto& [method, spp] : runs) ensure_compiled(scene, method, s);
  for (size_t first = 0; first < runs.size(); first += group) {
    const size_t end = std::min(runs.size(), first + group);
    std::vector<std::unique_ptr<EvalSession>> sessions;
    for (size_t i = first; i < end; ++i)
      sessions.push_back(std::make_unique<EvalSession>(*stub_, scene_source(scene), scene, runs[i].first, runs[i].second, s, timeout()));
    // The order rotates by one run each frame, so that no run always follows the same one: on
    // lavapipe a frame's time depends on what ran just before it (foliage: pt's frames read 225-230
    // ms where each followed a pt run, its frames under method auto 296-303 ms where each followed a
    // restir-gather run; docs/BENCHMARKS.md, "Method auto").
    const size_t n = end - first;
    for (uint32_t f = 0; f < s.frames; ++f)
      for (size_t k = 0; k < n; ++k) {
        const size_t i = first + (f + k) % n;
        on_frame(i, sessions[i - first]->next(f));
      }
    for (auto& session : sessions) session->finish();
  }
}

}  // namespace strata::client
