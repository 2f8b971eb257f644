#include "service/auth_gate.h"

namespace strata::service {
namespace {

// A stream refused before it starts: finishes with the status at once; gRPC deletes nothing, so
// the reactor deletes itself when the call is done.
class RefusedStream final : public grpc::ServerBidiReactor<v1::FrameInput, v1::Frame> {
 public:
  explicit RefusedStream(const grpc::Status& status) { Finish(status); }
  void OnDone() override { delete this; }
};

}  // namespace

grpc::Status AuthGatedRenderService::CreateSession(grpc::ServerContext* ctx, const v1::CreateSessionRequest* req,
                                                   v1::Session* resp) {
  if (auto st = token_.check(ctx->client_metadata()); !st.ok()) return st;
  return RenderServiceImpl::CreateSession(ctx, req, resp);
}

grpc::Status AuthGatedRenderService::GetSession(grpc::ServerContext* ctx, const v1::GetSessionRequest* req, v1::Session* resp) {
  if (auto st = token_.check(ctx->client_metadata()); !st.ok()) return st;
  return RenderServiceImpl::GetSession(ctx, req, resp);
}

grpc::Status AuthGatedRenderService::ListSessions(grpc::ServerContext* ctx, const v1::ListSessionsRequest* req,
                                                  v1::ListSessionsResponse* resp) {
  if (auto st = token_.check(ctx->client_metadata()); !st.ok()) return st;
  return RenderServiceImpl::ListSessions(ctx, req, resp);
}

grpc::Status AuthGatedRenderService::DeleteSession(grpc::ServerContext* ctx, const v1::DeleteSessionRequest* req,
                                                   google::protobuf::Empty* resp) {
  if (auto st = token_.check(ctx->client_metadata()); !st.ok()) return st;
  return RenderServiceImpl::DeleteSession(ctx, req, resp);
}

grpc::Status AuthGatedRenderService::ListScenes(grpc::ServerContext* ctx, const v1::ListScenesRequest* req,
                                                v1::ListScenesResponse* resp) {
  if (auto st = token_.check(ctx->client_metadata()); !st.ok()) return st;
  return RenderServiceImpl::ListScenes(ctx, req, resp);
}

grpc::Status AuthGatedRenderService::GetServerStatus(grpc::ServerContext* ctx, const v1::GetServerStatusRequest* req,
                                                     v1::ServerStatus* resp) {
  if (auto st = token_.check(ctx->client_metadata()); !st.ok()) return st;
  return RenderServiceImpl::GetServerStatus(ctx, req, resp);
}

grpc::ServerBidiReactor<v1::FrameInput, v1::Frame>* AuthGatedRenderService::Stream(grpc::CallbackServerContext* ctx) {
  if (auto st = token_.check(ctx->client_metadata()); !st.ok()) return new RefusedStream(st);
  return RenderServiceImpl::Stream(ctx);
}

grpc::Status AuthGatedRenderService::RenderReference(grpc::ServerContext* ctx, const v1::ReferenceRequest* req,
                                                     v1::Reference* resp) {
  if (auto st = token_.check(ctx->client_metadata()); !st.ok()) return st;
  return RenderServiceImpl::RenderReference(ctx, req, resp);
}

std::unique_ptr<RenderServiceImpl> make_render_service(ServiceCore& core) {
  const auto& path = core.config.security.auth_token_file;
  if (path.empty()) return std::make_unique<RenderServiceImpl>(core);
  return std::make_unique<AuthGatedRenderService>(core, BearerToken::load(path));
}

}  // namespace strata::service
