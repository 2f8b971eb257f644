#pragma once
// The service under test: a real strata::service::Server on 127.0.0.1 (a free port) with one
// Vulkan context per test binary (validation on), a client stub over real gRPC, and helpers to
// create sessions and stream frames. Every wait is bounded in time.
#include <gtest/gtest.h>

#include <chrono>
#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <grpcpp/grpcpp.h>

#include "gpu/context.h"
#include "image/image.h"
#include "service/server.h"
#include "strata/v1/render.grpc.pb.h"

namespace strata::test {

namespace v1 = ::strata::v1;
using namespace std::chrono_literals;

// The deadline of a call or process that may render with a pipeline lavapipe has not compiled yet:
// on a fresh clone (no shader cache) beside the restir suite and fuzz.build a restir-multilayer session's
// first frame took over 60 s (CI, DomainMapTest). A hang still fails, later.
inline constexpr std::chrono::seconds k_render_deadline = 300s;

gpu::Context& service_context();

// A temporary directory removed when the object goes.
struct TempDir {
  TempDir();
  ~TempDir();
  std::filesystem::path path;
};

// Small limits so that tests reach them cheaply.
service::ServiceConfig test_config(const std::filesystem::path& scene_dir);

// Channel with receive/send limits raised to `max_message_bytes`.
std::shared_ptr<grpc::Channel> loopback_channel(const std::string& address, int max_message_bytes = 64 << 20);

class ServiceTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  // (Re)starts the server with `config`; the stub talks to it.
  void start(service::ServiceConfig config);
  v1::RenderService::Stub& stub() { return *stub_; }
  const std::string& address() const { return server_->address(); }

  TempDir scene_dir_;
  service::ServiceConfig config_ = test_config(scene_dir_.path);
  std::unique_ptr<service::Server> server_;
  std::unique_ptr<v1::RenderService::Stub> stub_;
  uint64_t validation_errors_before_ = 0;
};

v1::CreateSessionRequest session_request(const std::string& builtin, uint32_t width, uint32_t height, uint32_t spp = 1,
                                         uint32_t seed = 0,
                                         std::vector<v1::ImageEncoding> encodings = {v1::IMAGE_ENCODING_RAW_RGBA16F});
grpc::Status create_session(v1::RenderService::Stub& stub, const v1::CreateSessionRequest& req, v1::Session* out);
// The session's decision called `name` (nullptr when it has none).
const v1::Decision* decision(const v1::Session& s, const std::string& name);
// Fails the test (and returns an empty session) when creation fails.
v1::Session create_ok(v1::RenderService::Stub& stub, const v1::CreateSessionRequest& req);
grpc::Status get_session(v1::RenderService::Stub& stub, const std::string& name, v1::Session* out);
grpc::Status delete_session(v1::RenderService::Stub& stub, const std::string& name);
v1::ServerStatus server_status(v1::RenderService::Stub& stub);

// One Stream call with a deadline.
class StreamClient {
 public:
  explicit StreamClient(v1::RenderService::Stub& stub, std::chrono::milliseconds deadline = k_render_deadline);
  bool send(const v1::FrameInput& in) { return rw_->Write(in); }
  std::optional<v1::Frame> read();
  // WritesDone, then reads what is left (into `rest` when given), then Finish.
  grpc::Status close(std::vector<v1::Frame>* rest = nullptr);
  grpc::Status finish();  // Finish (after reads returned false)
  void cancel() { ctx_.TryCancel(); }

 private:
  grpc::ClientContext ctx_;
  std::unique_ptr<grpc::ClientReaderWriter<v1::FrameInput, v1::Frame>> rw_;
};

// Another client streaming a session in lockstep on its own channel until stopped: the "other
// sessions" that must go on undisturbed while a test misbehaves.
class BackgroundStream {
 public:
  BackgroundStream(const std::string& address, const std::string& session);
  ~BackgroundStream();
  uint64_t frames() const { return frames_.load(); }
  // Stops after the frame in progress; returns the stream's status (OK when nothing went wrong).
  grpc::Status stop();

 private:
  std::atomic<bool> stop_{false};
  std::atomic<uint64_t> frames_{0};
  grpc::Status status_;
  bool consistent_ = true;
  std::thread thread_;
};

// FrameInput with `sequence`, the session name when given, and the default animation's frame.
v1::FrameInput frame_input(uint64_t sequence, const std::string& session = "", std::optional<uint32_t> animation_frame = {});

// Streams `frames` frames of the default animation in lockstep and closes the stream (expects OK).
std::vector<v1::Frame> stream_frames(v1::RenderService::Stub& stub, const std::string& session, uint32_t frames);

// The image of `encoding` in the frame, decoded (RAW_RGBA16F or EXR_HALF).
image::Image frame_image(const v1::Frame& frame, v1::ImageEncoding encoding = v1::IMAGE_ENCODING_RAW_RGBA16F);
const v1::Image* find_image(const v1::Frame& frame, v1::ImageEncoding encoding);

// Polls `done` every 5 ms until it is true or `timeout` passes; returns its last value.
bool wait_until(const std::function<bool()>& done, std::chrono::milliseconds timeout);

}  // namespace strata::test
