#pragma once
// The on-disk cache of converged references: one file per reference, named by a SHA-256
// content hash of everything the image depends on (the scene's content, the exact frame state,
// the settings and the renderer version). Writes are atomic (a temporary file in the same
// directory, flushed, then renamed), so concurrent or interrupted writers never leave a partial
// entry; every entry carries a checksum, and a corrupt or truncated one reads as absent (and is
// removed), so the reference is rendered again.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "image/image.h"
#include "scene/scene.h"

namespace strata::render {

// Bump when the reference path tracer's output changes in a way the SPIR-V hash does not show
// (host-side frame constants, scene upload, the accumulation scheme, the seed derivation).
constexpr uint32_t k_reference_renderer_version = 1;

// SHA-256 (OpenSSL's EVP implementation).
class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  void update(const void* data, size_t bytes);
  template <class T>
  void pod(const T& value) {
    update(&value, sizeof value);
  }
  template <class T>
  void array(const std::vector<T>& values) {
    pod(uint64_t(values.size()));
    if (!values.empty()) update(values.data(), values.size() * sizeof(T));
  }
  void text(const std::string& s);
  std::array<uint8_t, 32> finish();
  std::string finish_hex();

 private:
  void* ctx_;  // EVP_MD_CTX
};

std::string to_hex(const std::array<uint8_t, 32>& digest);

// Content hash of a scene: materials, meshes, instances, camera, environment and animation
// (names left out: they do not change the image).
std::string scene_content_hash(const scene::Scene& scene);

// Everything a reference image depends on.
struct ReferenceKey {
  std::string scene_hash;       // scene_content_hash
  // The resolved state: camera (its shutter included), where the shutter opened (motion blur,
  // RS-main 4.4; none for an instant), every transform, every LoD level.
  scene::FrameState frame;
  uint32_t width = 0, height = 0, max_depth = 0, seed = 0, spp = 0;
  float relative_error = 0.0f;  // the early-stop target (0: none)
};
// Hex SHA-256 of the key, the renderer version and the SPIR-V of the path tracer.
std::string reference_cache_key(const ReferenceKey& key);

// A rendered reference as stored.
struct ReferenceEntry {
  image::Image image;
  uint32_t spp = 0;
  uint32_t batches = 0;
  double relative_error = 0.0;
  bool relative_error_reached = false;
  double gpu_ms = 0.0;
};

class ReferenceCache {
 public:
  // The directory is created on first store.
  explicit ReferenceCache(std::filesystem::path dir);
  const std::filesystem::path& dir() const { return dir_; }
  std::filesystem::path path_of(const std::string& key) const;  // DIR/<key>.ref

  // The entry, or nullopt when there is none or it is corrupt (a corrupt file is removed, and
  // `why` says what was wrong with it when given).
  std::optional<ReferenceEntry> load(const std::string& key, std::string* why = nullptr) const;
  // Writes atomically; throws std::runtime_error naming the file when it cannot.
  void store(const std::string& key, const ReferenceEntry& entry) const;

  // $XDG_CACHE_HOME/strata/references, else $HOME/.cache/strata/references, else
  // <temp>/strata-references-<uid>.
  static std::filesystem::path default_dir();

 private:
  std::filesystem::path dir_;
};

}  // namespace strata::render
