#include "service/render_service.h"

#include <algorithm>

#include "render/method_table.h"
#include "service/errors.h"
#include "service/method_auto.h"
#include "service/scene_source.h"
#include "service/session_spec.h"
#include "service/stream_reactor.h"

namespace strata::service {
namespace {

constexpr int k_default_page_size = 50, k_max_page_size = 1000;

void set_duration(google::protobuf::Duration* d, std::chrono::nanoseconds ns) {
  d->set_seconds(ns.count() / 1'000'000'000);
  d->set_nanos(int32_t(ns.count() % 1'000'000'000));
}

}  // namespace

grpc::Status RenderServiceImpl::CreateSession(grpc::ServerContext*, const v1::CreateSessionRequest* req, v1::Session* resp) {
  return guarded([&] {
    if (core_.draining.load()) fail(grpc::StatusCode::UNAVAILABLE, "stratad is draining (shutting down): no new sessions");
    const SessionSpec spec = check_create_session(*req, core_.config.limits);
    auto session = core_.registry.create(req->session_id(), "session_id", [&](const std::string& name) {
      auto scene = load_scene_source(req->scene(), core_.config);
      return std::make_shared<Session>(name, std::move(scene), spec, core_.ctx, core_.metrics, core_.progressive_start());
    });
    *resp = session->describe(core_.config);
  });
}

grpc::Status RenderServiceImpl::GetSession(grpc::ServerContext*, const v1::GetSessionRequest* req, v1::Session* resp) {
  return guarded([&] {
    auto s = core_.registry.get(req->name(), "name");
    s->touch();
    *resp = s->describe(core_.config);
  });
}

grpc::Status RenderServiceImpl::ListSessions(grpc::ServerContext*, const v1::ListSessionsRequest* req,
                                             v1::ListSessionsResponse* resp) {
  return guarded([&] {
    if (req->page_size() < 0) fail_invalid("page_size = " + std::to_string(req->page_size()) + " must be >= 0");
    const int size = req->page_size() == 0 ? k_default_page_size : std::min(req->page_size(), k_max_page_size);
    const std::string& token = req->page_token();
    if (!token.empty() && !is_session_name(token))
      fail_invalid("page_token = '" + token + "' is not a token returned by ListSessions");
    int n = 0;
    for (const auto& s : core_.registry.list()) {  // ordered by name
      if (!token.empty() && s->name() <= token) continue;
      if (n == size) {
        resp->set_next_page_token(resp->sessions(n - 1).name());
        break;
      }
      *resp->add_sessions() = s->describe(core_.config);
      ++n;
    }
  });
}

grpc::Status RenderServiceImpl::DeleteSession(grpc::ServerContext*, const v1::DeleteSessionRequest* req, google::protobuf::Empty*) {
  return guarded([&] {
    auto s = core_.registry.get(req->name(), "name");
    if (!core_.registry.remove(s->name(), "was deleted"))
      fail(grpc::StatusCode::NOT_FOUND, "session '" + req->name() + "' was removed meanwhile");
  });
}

grpc::Status RenderServiceImpl::ListScenes(grpc::ServerContext*, const v1::ListScenesRequest*, v1::ListScenesResponse* resp) {
  return guarded([&] {
    for (auto& e : list_scenes(core_.config)) *resp->add_scenes() = std::move(e);
  });
}

grpc::Status RenderServiceImpl::GetServerStatus(grpc::ServerContext*, const v1::GetServerStatusRequest*, v1::ServerStatus* resp) {
  return guarded([&] {
    const auto& cfg = core_.config;
    const auto& l = cfg.limits;
    resp->set_device(core_.ctx.device_name());
    resp->set_draining(core_.draining.load());
    auto* lim = resp->mutable_limits();
    lim->set_max_sessions(l.max_sessions);
    lim->set_max_pixels(l.max_pixels);
    lim->set_max_dimension(l.max_dimension);
    lim->set_max_scene_bytes(l.max_scene_bytes);
    lim->set_max_instances(l.max_instances);
    lim->set_max_spp(l.max_spp);
    lim->set_max_depth(l.max_depth);
    lim->set_max_frame_bytes(max_frame_bytes(l.max_pixels));
    set_duration(lim->mutable_idle_timeout(), cfg.idle_timeout);
    lim->set_scene_dir(cfg.scene_dir.string());
    lim->set_max_reference_spp(l.max_reference_spp);
    lim->set_max_environment_bytes(l.max_environment_bytes);
    lim->set_max_environment_dimension(l.max_environment_dimension);
    for (const auto& m : session_methods()) resp->add_methods(m);
    uint64_t device_bytes = 0;
    const auto sessions = core_.registry.list();
    for (const auto& s : sessions) device_bytes += s->device_bytes();
    resp->set_sessions(uint32_t(sessions.size()));
    resp->set_streams(core_.metrics.streams.load());
    resp->set_device_memory_bytes(device_bytes);
    resp->set_buffered_frame_bytes(uint64_t(std::max<int64_t>(0, core_.metrics.buffered_frame_bytes.load())));
    resp->set_sessions_created(core_.metrics.sessions_created.load());
    resp->set_sessions_expired(core_.metrics.sessions_expired.load());
    resp->set_frames_rendered(core_.metrics.frames_rendered.load());
    resp->set_frames_dropped(core_.metrics.frames_dropped.load());
    resp->set_inputs_coalesced(core_.metrics.inputs_coalesced.load());
    set_duration(resp->mutable_uptime(), std::chrono::steady_clock::now() - core_.started);
  });
}

grpc::ServerBidiReactor<v1::FrameInput, v1::Frame>* RenderServiceImpl::Stream(grpc::CallbackServerContext* ctx) {
  return StreamReactor::start(core_, ctx);
}

grpc::Status RenderServiceImpl::RenderReference(grpc::ServerContext* ctx, const v1::ReferenceRequest* req, v1::Reference* resp) {
  return references_.render(ctx, *req, resp);  // service/reference_service.cpp
}

}  // namespace strata::service
