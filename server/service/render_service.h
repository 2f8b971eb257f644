#pragma once
// strata.v1.RenderService: the unary RPCs on gRPC's synchronous thread pool, Stream on the
// callback API (StreamReactor).
#include <grpcpp/grpcpp.h>

#include "service/reference_service.h"
#include "service/service_core.h"
#include "strata/v1/render.grpc.pb.h"

namespace strata::service {

class RenderServiceImpl : public v1::RenderService::WithCallbackMethod_Stream<v1::RenderService::Service> {
 public:
  explicit RenderServiceImpl(ServiceCore& core) : core_(core) {}

  grpc::Status CreateSession(grpc::ServerContext*, const v1::CreateSessionRequest* req, v1::Session* resp) override;
  grpc::Status GetSession(grpc::ServerContext*, const v1::GetSessionRequest* req, v1::Session* resp) override;
  grpc::Status ListSessions(grpc::ServerContext*, const v1::ListSessionsRequest* req, v1::ListSessionsResponse* resp) override;
  grpc::Status DeleteSession(grpc::ServerContext*, const v1::DeleteSessionRequest* req, google::protobuf::Empty*) override;
  grpc::Status ListScenes(grpc::ServerContext*, const v1::ListScenesRequest*, v1::ListScenesResponse* resp) override;
  grpc::Status GetServerStatus(grpc::ServerContext*, const v1::GetServerStatusRequest*, v1::ServerStatus* resp) override;
  grpc::ServerBidiReactor<v1::FrameInput, v1::Frame>* Stream(grpc::CallbackServerContext* ctx) override;
  grpc::Status RenderReference(grpc::ServerContext* ctx, const v1::ReferenceRequest* req, v1::Reference* resp) override;

 private:
  ServiceCore& core_;
  ReferenceService references_{core_};
};

}  // namespace strata::service
