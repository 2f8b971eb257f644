#pragma once
// RenderService behind the bearer token: every RPC of strata.v1.RenderService checks the token
// before it does anything, and a call without the right one ends with UNAUTHENTICATED.
//
// Why not an interceptor or an AuthMetadataProcessor: grpc 1.51's AuthMetadataProcessor aborts the
// process on insecure credentials, and its server interceptors cannot end a call (no Hijack on the
// server side), so a rejecting interceptor would still run the handler. The check therefore sits
// in front of every handler; tests/security checks that every method the service declares is
// gated, so an RPC added later cannot slip through. grpc.health.v1 stays open: load balancers and
// kubelets probe it without credentials, and it reveals only SERVING or NOT_SERVING.
#include <memory>

#include "service/auth_token.h"
#include "service/render_service.h"

namespace strata::service {

class AuthGatedRenderService final : public RenderServiceImpl {
 public:
  AuthGatedRenderService(ServiceCore& core, BearerToken token) : RenderServiceImpl(core), token_(std::move(token)) {}

  grpc::Status CreateSession(grpc::ServerContext* ctx, const v1::CreateSessionRequest* req, v1::Session* resp) override;
  grpc::Status GetSession(grpc::ServerContext* ctx, const v1::GetSessionRequest* req, v1::Session* resp) override;
  grpc::Status ListSessions(grpc::ServerContext* ctx, const v1::ListSessionsRequest* req, v1::ListSessionsResponse* resp) override;
  grpc::Status DeleteSession(grpc::ServerContext* ctx, const v1::DeleteSessionRequest* req, google::protobuf::Empty* resp) override;
  grpc::Status ListScenes(grpc::ServerContext* ctx, const v1::ListScenesRequest* req, v1::ListScenesResponse* resp) override;
  grpc::Status GetServerStatus(grpc::ServerContext* ctx, const v1::GetServerStatusRequest* req, v1::ServerStatus* resp) override;
  grpc::ServerBidiReactor<v1::FrameInput, v1::Frame>* Stream(grpc::CallbackServerContext* ctx) override;
  grpc::Status RenderReference(grpc::ServerContext* ctx, const v1::ReferenceRequest* req, v1::Reference* resp) override;

 private:
  BearerToken token_;
};

// The service stratad serves: gated when the configuration names a token file (which is read
// here; std::invalid_argument when it is unusable), else the plain one.
std::unique_ptr<RenderServiceImpl> make_render_service(ServiceCore& core);

}  // namespace strata::service
