// grpc.health.v1 health checking and server reflection on the render service.
#include <google/protobuf/descriptor.h>
#include <google/protobuf/dynamic_message.h>
#include <grpcpp/impl/codegen/client_unary_call.h>
#include <grpcpp/impl/codegen/sync_stream.h>

#include "grpc/health/v1/health.grpc.pb.h"
#include "harness.h"

namespace strata::test {
namespace {

using grpc::health::v1::HealthCheckRequest;
using grpc::health::v1::HealthCheckResponse;
using HealthReflectionTest = ServiceTest;

TEST_F(HealthReflectionTest, HealthIsServingForTheServerAndTheRenderService) {
  auto health = grpc::health::v1::Health::NewStub(loopback_channel(address()));
  for (const std::string service : {"", "strata.v1.RenderService"}) {
    grpc::ClientContext ctx;
    HealthCheckRequest req;
    req.set_service(service);
    HealthCheckResponse resp;
    const grpc::Status st = health->Check(&ctx, req, &resp);
    ASSERT_TRUE(st.ok()) << "'" << service << "': " << st.error_message();
    EXPECT_EQ(resp.status(), HealthCheckResponse::SERVING) << "'" << service << "'";
  }
  grpc::ClientContext ctx;
  HealthCheckRequest req;
  req.set_service("no.such.Service");
  HealthCheckResponse resp;
  EXPECT_EQ(health->Check(&ctx, req, &resp).error_code(), grpc::StatusCode::NOT_FOUND);
}

// Reflection through the descriptors that libgrpc++_reflection registers (no generated header is
// installed for them): list the services the server offers.
TEST_F(HealthReflectionTest, ReflectionListsTheServices) {
  const auto* pool = google::protobuf::DescriptorPool::generated_pool();
  const auto* req_type = pool->FindMessageTypeByName("grpc.reflection.v1alpha.ServerReflectionRequest");
  const auto* resp_type = pool->FindMessageTypeByName("grpc.reflection.v1alpha.ServerReflectionResponse");
  ASSERT_NE(req_type, nullptr);
  ASSERT_NE(resp_type, nullptr);
  auto* factory = google::protobuf::MessageFactory::generated_factory();
  std::unique_ptr<google::protobuf::Message> req(factory->GetPrototype(req_type)->New());
  std::unique_ptr<google::protobuf::Message> resp(factory->GetPrototype(resp_type)->New());
  req->GetReflection()->SetString(req.get(), req_type->FindFieldByName("list_services"), "*");

  auto channel = loopback_channel(address());
  const grpc::internal::RpcMethod method("/grpc.reflection.v1alpha.ServerReflection/ServerReflectionInfo",
                                         grpc::internal::RpcMethod::BIDI_STREAMING);
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + 10s);
  std::unique_ptr<grpc::ClientReaderWriter<google::protobuf::Message, google::protobuf::Message>> rw(
      grpc::internal::ClientReaderWriterFactory<google::protobuf::Message, google::protobuf::Message>::Create(
          channel.get(), method, &ctx));
  ASSERT_TRUE(rw->Write(*req));
  rw->WritesDone();
  ASSERT_TRUE(rw->Read(resp.get()));
  EXPECT_TRUE(rw->Finish().ok());
  const std::string text = resp->DebugString();
  EXPECT_NE(text.find("strata.v1.RenderService"), std::string::npos) << text;
  EXPECT_NE(text.find("grpc.health.v1.Health"), std::string::npos) << text;
}

}  // namespace
}  // namespace strata::test
