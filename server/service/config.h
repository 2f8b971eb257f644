#pragma once
// What `stratad serve` is configured with: where it listens, where scene files may come from, and
// the limits every request is held to (each violation names the field and the limit).
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace strata::service {

struct ServiceLimits {
  uint32_t max_sessions = 8;
  uint64_t max_pixels = 1920ull * 1080;   // width * height of one session
  uint32_t max_dimension = 8192;          // width and height each
  uint64_t max_scene_bytes = 64ull << 20;  // inline .glb, and files in the scene directory
  uint64_t max_texture_bytes = 256ull << 20;  // a scene's decoded textures, RGBA8 with mip levels
  uint32_t max_instances = 4096;
  uint32_t max_spp = 1024;
  uint32_t max_depth = 64;
  uint32_t max_reference_spp = 65536;     // RenderReference: target samples per pixel
  uint64_t max_environment_bytes = 64ull << 20;  // an environment file, inline or in the scene directory
  uint32_t max_environment_dimension = 4096;     // its width and height each (16 B of device memory a texel)
};

// Pipelines compiled ahead of their first dispatch (service/warm_up.h); `stratad serve` sets these.
struct CompileConfig {
  std::string device;                // the compiling devices' gpu::ContextOptions::device (the service's)
  std::vector<std::string> warm_up;  // methods whose pipelines compile at start (`--warm-up`)
  unsigned threads = 1;              // devices compiling in parallel
  // A session whose method's pipelines are not compiled yet renders with pt meanwhile and takes
  // its method from the frame after they are (service/session.h). Off: the first frame compiles them.
  bool progressive_start = false;
};

// Transport security and authentication (service/tls_credentials.cpp, service/auth_token.cpp).
struct SecurityConfig {
  std::filesystem::path tls_cert, tls_key;  // PEM; both or neither: TLS
  std::filesystem::path tls_client_ca;      // PEM; with TLS: clients must present a certificate it signed (mTLS)
  std::filesystem::path auth_token_file;    // every RenderService call needs `authorization: Bearer <token>`
  bool insecure = false;                    // allow plaintext without a token beyond loopback
};

struct ServiceConfig {
  std::string listen = "127.0.0.1:50051";    // host:port; port 0 picks a free one
  std::string instance_id;                   // sent as x-strata-instance on every response; empty: host:port
  SecurityConfig security;
  std::filesystem::path scene_dir;           // allow-listed scene directory; empty refuses paths
  ServiceLimits limits;
  std::chrono::milliseconds idle_timeout{std::chrono::minutes(5)};  // idle sessions expire
  std::chrono::milliseconds drain_timeout{std::chrono::seconds(10)};  // SIGTERM: frames in flight
  std::chrono::milliseconds end_grace{std::chrono::seconds(2)};  // a stream being ended whose write does not complete is cancelled after this
  uint32_t encode_threads = 2;
  std::filesystem::path reference_cache;     // RenderReference's cache; empty: render::ReferenceCache::default_dir()
  CompileConfig compile;
  // Throws std::invalid_argument naming the setting and its allowed range.
  void validate() const;
};

// Upper bound of a Frame message for `pixels` pixels with every encoding at once (raw RGBA16F
// 8 B/px, EXR half with ZIP at most 9 B/px, the preview and domain map PNGs at most 4 B/px each,
// plus headers and statistics).
uint64_t max_frame_bytes(uint64_t pixels);

}  // namespace strata::service
