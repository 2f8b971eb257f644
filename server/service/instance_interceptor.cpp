#include "service/instance_interceptor.h"

#include <stdexcept>

namespace strata::service {
namespace {

class InstanceInterceptor final : public grpc::experimental::Interceptor {
 public:
  explicit InstanceInterceptor(const std::string& id) : id_(id) {}
  void Intercept(grpc::experimental::InterceptorBatchMethods* methods) override {
    if (methods->QueryInterceptionHookPoint(grpc::experimental::InterceptionHookPoints::PRE_SEND_INITIAL_METADATA))
      methods->GetSendInitialMetadata()->emplace(k_instance_metadata, id_);
    methods->Proceed();
  }

 private:
  const std::string& id_;  // owned by the factory, which outlives the server's calls
};

class InstanceInterceptorFactory final : public grpc::experimental::ServerInterceptorFactoryInterface {
 public:
  explicit InstanceInterceptorFactory(std::string id) : id_(std::move(id)) {}
  grpc::experimental::Interceptor* CreateServerInterceptor(grpc::experimental::ServerRpcInfo*) override {
    return new InstanceInterceptor(id_);
  }

 private:
  std::string id_;
};

}  // namespace

std::vector<std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface>> instance_interceptors(std::string instance_id) {
  // A metadata value must be printable ASCII; the id also appears in proxies' logs.
  if (instance_id.empty() || instance_id.size() > 128)
    throw std::invalid_argument("--instance-id has " + std::to_string(instance_id.size()) + " characters; it must have 1-128");
  for (char c : instance_id)
    if (c < 0x21 || c > 0x7e) throw std::invalid_argument("--instance-id may only hold printable ASCII characters without spaces");
  std::vector<std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface>> out;
  out.push_back(std::make_unique<InstanceInterceptorFactory>(std::move(instance_id)));
  return out;
}

}  // namespace strata::service
