#include "harness.h"

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <random>

#include "service/encoding.h"

namespace strata::test {

gpu::Context& service_context() {
  static std::unique_ptr<gpu::Context> ctx = [] {
    gpu::ContextOptions options;
    options.validation = true;
    return std::make_unique<gpu::Context>(options);
  }();
  return *ctx;
}

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  std::random_device rd;
  path = std::filesystem::temp_directory_path() /
         ("strata_service_" + std::to_string(rd()) + "_" + std::to_string(counter.fetch_add(1)));
  std::filesystem::create_directories(path);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path, ec);
}

service::ServiceConfig test_config(const std::filesystem::path& scene_dir) {
  service::ServiceConfig c;
  c.listen = "127.0.0.1:0";
  c.scene_dir = scene_dir;
  c.limits.max_sessions = 4;
  c.limits.max_pixels = 640 * 480;
  c.limits.max_dimension = 1024;
  c.limits.max_scene_bytes = 256 << 10;
  c.limits.max_environment_bytes = 64 << 10;
  c.limits.max_instances = 64;
  c.limits.max_spp = 64;
  c.limits.max_depth = 32;
  c.idle_timeout = 60s;
  c.drain_timeout = 3s;
  c.end_grace = 1s;
  return c;
}

std::shared_ptr<grpc::Channel> loopback_channel(const std::string& address, int max_message_bytes) {
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(max_message_bytes);
  args.SetMaxSendMessageSize(max_message_bytes);
  return grpc::CreateCustomChannel(address, grpc::InsecureChannelCredentials(), args);
}

void ServiceTest::SetUp() {
  validation_errors_before_ = service_context().validation_errors();
  start(config_);
}

void ServiceTest::TearDown() {
  stub_.reset();
  server_.reset();
  auto& ctx = service_context();
  EXPECT_EQ(ctx.validation_errors(), validation_errors_before_) << [&] {
    std::string all = "Vulkan validation errors during this test:\n";
    for (const auto& m : ctx.validation_messages()) all += m + "\n";
    return all;
  }();
}

void ServiceTest::start(service::ServiceConfig config) {
  stub_.reset();
  server_.reset();
  config_ = std::move(config);
  server_ = std::make_unique<service::Server>(service_context(), config_);
  stub_ = v1::RenderService::NewStub(loopback_channel(server_->address()));
}

v1::CreateSessionRequest session_request(const std::string& builtin, uint32_t width, uint32_t height, uint32_t spp,
                                         uint32_t seed, std::vector<v1::ImageEncoding> encodings) {
  v1::CreateSessionRequest r;
  r.mutable_scene()->set_builtin(builtin);
  r.mutable_resolution()->set_width(width);
  r.mutable_resolution()->set_height(height);
  r.set_method("pt");
  r.mutable_options()->set_spp(spp);
  r.set_seed(seed);
  for (auto e : encodings) r.add_encodings(e);
  return r;
}

grpc::Status create_session(v1::RenderService::Stub& stub, const v1::CreateSessionRequest& req, v1::Session* out) {
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + k_render_deadline);
  return stub.CreateSession(&ctx, req, out);
}

v1::Session create_ok(v1::RenderService::Stub& stub, const v1::CreateSessionRequest& req) {
  v1::Session s;
  grpc::Status st = create_session(stub, req, &s);
  EXPECT_TRUE(st.ok()) << "CreateSession: " << st.error_code() << " " << st.error_message();
  return s;
}

grpc::Status get_session(v1::RenderService::Stub& stub, const std::string& name, v1::Session* out) {
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + 30s);
  v1::GetSessionRequest req;
  req.set_name(name);
  return stub.GetSession(&ctx, req, out);
}

grpc::Status delete_session(v1::RenderService::Stub& stub, const std::string& name) {
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + 30s);
  v1::DeleteSessionRequest req;
  req.set_name(name);
  google::protobuf::Empty empty;
  return stub.DeleteSession(&ctx, req, &empty);
}

v1::ServerStatus server_status(v1::RenderService::Stub& stub) {
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + 30s);
  v1::ServerStatus s;
  grpc::Status st = stub.GetServerStatus(&ctx, {}, &s);
  EXPECT_TRUE(st.ok()) << st.error_message();
  return s;
}

StreamClient::StreamClient(v1::RenderService::Stub& stub, std::chrono::milliseconds deadline) {
  ctx_.set_deadline(std::chrono::system_clock::now() + deadline);
  rw_ = stub.Stream(&ctx_);
}

std::optional<v1::Frame> StreamClient::read() {
  v1::Frame f;
  if (!rw_->Read(&f)) return std::nullopt;
  return f;
}

grpc::Status StreamClient::close(std::vector<v1::Frame>* rest) {
  rw_->WritesDone();
  v1::Frame f;
  while (rw_->Read(&f))
    if (rest) rest->push_back(f);
  return rw_->Finish();
}

grpc::Status StreamClient::finish() { return rw_->Finish(); }

BackgroundStream::BackgroundStream(const std::string& address, const std::string& session) {
  thread_ = std::thread([this, address, session] {
    auto stub = v1::RenderService::NewStub(loopback_channel(address));
    StreamClient c(*stub, 300s);
    for (uint64_t i = 1; !stop_.load() && i < 1'000'000; ++i) {
      if (!c.send(frame_input(i, i == 1 ? session : "", uint32_t(i % 30)))) break;
      auto f = c.read();
      if (!f) break;
      if (f->input_sequence() != i || f->images_size() == 0) consistent_ = false;
      frames_.fetch_add(1);
    }
    status_ = c.close();
    if (status_.ok() && !consistent_) status_ = grpc::Status(grpc::StatusCode::INTERNAL, "a frame answered the wrong input");
  });
}

BackgroundStream::~BackgroundStream() { stop(); }

grpc::Status BackgroundStream::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  return status_;
}

v1::FrameInput frame_input(uint64_t sequence, const std::string& session, std::optional<uint32_t> animation_frame) {
  v1::FrameInput in;
  in.set_sequence(sequence);
  if (!session.empty()) in.set_session(session);
  if (animation_frame) in.set_animation_frame(*animation_frame);
  return in;
}

std::vector<v1::Frame> stream_frames(v1::RenderService::Stub& stub, const std::string& session, uint32_t frames) {
  std::vector<v1::Frame> out;
  StreamClient s(stub);
  for (uint32_t i = 0; i < frames; ++i) {
    if (!s.send(frame_input(i + 1, i == 0 ? session : "", i))) break;
    auto f = s.read();
    if (!f) break;
    out.push_back(std::move(*f));
  }
  grpc::Status st = s.close();
  EXPECT_TRUE(st.ok()) << "Stream: " << st.error_code() << " " << st.error_message();
  EXPECT_EQ(out.size(), frames);
  return out;
}

const v1::Image* find_image(const v1::Frame& frame, v1::ImageEncoding encoding) {
  for (const auto& img : frame.images())
    if (img.encoding() == encoding) return &img;
  return nullptr;
}

image::Image frame_image(const v1::Frame& frame, v1::ImageEncoding encoding) {
  const v1::Image* img = find_image(frame, encoding);
  if (!img) throw std::runtime_error("frame has no image of encoding " + std::to_string(int(encoding)));
  const auto& d = img->data();
  std::vector<uint8_t> bytes(d.begin(), d.end());
  if (encoding == v1::IMAGE_ENCODING_EXR_HALF) return image::decode_exr(bytes);
  return image::decode_rgba16f(bytes, img->width(), img->height());
}

bool wait_until(const std::function<bool()>& done, std::chrono::milliseconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    if (std::chrono::steady_clock::now() >= until) return done();
    std::this_thread::sleep_for(5ms);
  }
  return true;
}

const v1::Decision* decision(const v1::Session& s, const std::string& name) {
  for (const auto& d : s.decisions())
    if (d.name() == name) return &d;
  return nullptr;
}

}  // namespace strata::test
