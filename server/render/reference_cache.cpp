#include "render/reference_cache.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include <fcntl.h>
#include <openssl/evp.h>
#include <unistd.h>

#include "embedded_shaders.h"
#include "render/renderer.h"

namespace strata::render {
namespace {

namespace fs = std::filesystem;

constexpr char k_magic[8] = {'S', 'T', 'R', 'R', 'E', 'F', '\x01', '\n'};
constexpr uint32_t k_format = 1;
constexpr size_t k_key_chars = 64;
// magic, format, key, width, height, spp, batches, reached, relative error, gpu ms
constexpr size_t k_header_bytes = sizeof k_magic + 4 + k_key_chars + 5 * 4 + 2 * 8;
constexpr size_t k_digest_bytes = 32;

EVP_MD_CTX* md(void* p) { return static_cast<EVP_MD_CTX*>(p); }

void hash_camera(Sha256& h, const scene::Camera& c) {
  h.pod(c.position);
  h.pod(c.orientation);
  h.pod(c.yfov);
  h.pod(c.aperture);
  h.pod(c.focus_distance);
  h.pod(c.shutter);
}

template <class T>
T get(const std::vector<uint8_t>& in, size_t& at) {
  T v;
  std::memcpy(&v, in.data() + at, sizeof v);
  at += sizeof v;
  return v;
}

std::atomic<uint64_t> g_temp_counter{0};

}  // namespace

// ---- hashing ---------------------------------------------------------------------------------

Sha256::Sha256() : ctx_(EVP_MD_CTX_new()) {
  if (!ctx_ || EVP_DigestInit_ex(md(ctx_), EVP_sha256(), nullptr) != 1) throw std::runtime_error("SHA-256: cannot initialise OpenSSL");
}

Sha256::~Sha256() { EVP_MD_CTX_free(md(ctx_)); }

void Sha256::update(const void* data, size_t bytes) {
  if (bytes && EVP_DigestUpdate(md(ctx_), data, bytes) != 1) throw std::runtime_error("SHA-256: update failed");
}

void Sha256::text(const std::string& s) {
  pod(uint64_t(s.size()));
  update(s.data(), s.size());
}

std::array<uint8_t, 32> Sha256::finish() {
  std::array<uint8_t, 32> d{};
  unsigned int n = 0;
  if (EVP_DigestFinal_ex(md(ctx_), d.data(), &n) != 1 || n != d.size()) throw std::runtime_error("SHA-256: final failed");
  return d;
}

std::string Sha256::finish_hex() { return to_hex(finish()); }

std::string to_hex(const std::array<uint8_t, 32>& digest) {
  static const char* digits = "0123456789abcdef";
  std::string s;
  s.reserve(64);
  for (uint8_t b : digest) {
    s.push_back(digits[b >> 4]);
    s.push_back(digits[b & 15]);
  }
  return s;
}

namespace {

void hash_texture_ref(Sha256& h, const scene::TextureRef& r) {
  h.pod(r.texture);
  h.pod(r.tex_coord);
  h.pod(r.transform.offset);
  h.pod(r.transform.rotation);
  h.pod(r.transform.scale);
}

void hash_keys(Sha256& h, const std::vector<scene::TransformKey>& keys) {
  h.pod(uint64_t(keys.size()));
  for (const auto& k : keys) {
    h.pod(k.time);
    h.pod(k.translation);
    h.pod(k.rotation);
    h.pod(k.scale);
  }
}

}  // namespace

std::string scene_content_hash(const scene::Scene& s) {
  Sha256 h;
  h.text("strata scene content v2");
  h.pod(uint64_t(s.materials.size()));
  for (const auto& m : s.materials) {
    h.pod(m.base_color);
    h.pod(m.metallic);
    h.pod(m.roughness);
    h.pod(m.emission);
    h.pod(m.specular);
    h.pod(uint8_t(m.double_sided));
    h.pod(m.alpha);
    h.pod(uint8_t(m.alpha_mode));
    h.pod(m.alpha_cutoff);
    hash_texture_ref(h, m.base_color_texture);
    hash_texture_ref(h, m.metallic_roughness_texture);
    hash_texture_ref(h, m.normal_texture);
    h.pod(m.normal_scale);
    hash_texture_ref(h, m.emissive_texture);
  }
  const scene::TextureSet& t = s.textures;
  h.pod(uint64_t(t.images.size()));
  for (const auto& i : t.images) {
    h.pod(uint8_t(i.color_space));
    h.pod(i.first_level);
    h.pod(i.level_count);
  }
  h.pod(uint64_t(t.levels.size()));
  for (const auto& l : t.levels) {
    h.pod(l.width);
    h.pod(l.height);
    h.pod(l.offset);
  }
  h.pod(uint64_t(t.textures.size()));
  for (const auto& x : t.textures) {
    h.pod(x.image);
    h.pod(uint8_t(x.sampler.mag_filter));
    h.pod(uint8_t(x.sampler.min_filter));
    h.pod(uint8_t(x.sampler.mip_filter));
    h.pod(uint8_t(x.sampler.wrap_u));
    h.pod(uint8_t(x.sampler.wrap_v));
  }
  h.array(t.texels);
  h.pod(uint64_t(s.meshes.size()));
  for (const auto& mesh : s.meshes) {
    h.pod(uint64_t(mesh.primitives.size()));
    for (const auto& p : mesh.primitives) {
      h.array(p.positions);
      h.array(p.normals);
      h.array(p.uvs);
      h.array(p.uvs1);
      h.array(p.tangents);
      h.array(p.indices);
      h.pod(p.material);
    }
  }
  h.pod(uint64_t(s.instances.size()));
  for (const auto& i : s.instances) {
    h.array(i.lod_meshes);
    h.pod(i.transform);
    h.pod(i.lod);
  }
  hash_camera(h, s.camera);
  h.pod(uint64_t(s.lights.size()));
  for (const auto& l : s.lights) {
    h.pod(uint8_t(l.type));
    h.pod(l.color);
    h.pod(l.intensity);
    h.pod(l.range);
    h.pod(l.inner_cone);
    h.pod(l.outer_cone);
    h.pod(l.transform);
  }
  h.pod(s.environment.radiance);
  h.pod(uint8_t(s.environment.map.has_value()));
  if (s.environment.map) {
    const scene::EnvironmentMap& e = *s.environment.map;
    h.pod(e.width);
    h.pod(e.height);
    h.array(e.radiance);
    h.pod(e.intensity);
    h.pod(e.rotation);
  }
  const auto& a = s.animation;
  h.pod(a.frames_per_second);
  h.pod(uint64_t(a.camera.size()));
  for (const auto& k : a.camera) {
    h.pod(k.time);
    h.pod(k.position);
    h.pod(k.orientation);
  }
  h.pod(uint64_t(a.tracks.size()));
  for (const auto& tr : a.tracks) {
    h.pod(tr.instance);
    hash_keys(h, tr.keys);
  }
  h.pod(uint64_t(a.light_tracks.size()));
  for (const auto& tr : a.light_tracks) {
    h.pod(tr.light);
    hash_keys(h, tr.keys);
  }
  h.pod(uint64_t(a.lod_schedule.size()));
  for (const auto& k : a.lod_schedule) {
    h.pod(k.time);
    h.pod(k.instance);
    h.pod(k.level);
  }
  // Deforming meshes, hashed only where a scene has them (the keys of every other scene stay).
  const bool deforming = !s.skins.empty() || std::any_of(s.instances.begin(), s.instances.end(), [](const auto& i) { return i.deforms(); });
  if (deforming) {
    h.text("deforming meshes");
    for (const auto& skin : s.skins) {
      h.array(skin.inverse_bind);
      h.array(skin.joints);
    }
    for (const auto& mesh : s.meshes) {
      h.array(mesh.weights);
      for (const auto& p : mesh.primitives) {
        h.array(p.joints);
        h.array(p.weights);
        h.pod(uint64_t(p.targets.size()));
        for (const auto& target : p.targets) {
          h.array(target.positions);
          h.array(target.normals);
        }
      }
    }
    for (const auto& i : s.instances) {
      h.pod(i.skin);
      h.array(i.morph_weights);
    }
    for (const auto& tr : a.joint_tracks) {
      h.pod(tr.skin);
      h.pod(tr.joint);
      hash_keys(h, tr.keys);
    }
    for (const auto& tr : a.morph_tracks) {
      h.pod(tr.instance);
      for (const auto& k : tr.keys) {
        h.pod(k.time);
        h.array(k.weights);
      }
    }
  }
  return h.finish_hex();
}

std::string reference_cache_key(const ReferenceKey& k) {
  Sha256 h;
  h.text("strata reference");
  h.pod(k_reference_renderer_version);
  const auto spirv = shaders::spirv("path_trace");  // any change of the path tracer's code
  h.update(spirv.data(), spirv.size_bytes());
  h.pod(RenderSettings{}.samples_per_dispatch);
  h.text(k.scene_hash);
  hash_camera(h, k.frame.camera);
  h.pod(uint8_t(k.frame.camera_open.has_value()));
  if (k.frame.camera_open) hash_camera(h, *k.frame.camera_open);
  h.array(k.frame.transforms);
  h.array(k.frame.lods);
  h.array(k.frame.lights);
  for (size_t i = 0; i < k.frame.joints.size(); ++i)
    if (!k.frame.joints[i].empty()) h.array(k.frame.joints[i]);
  for (size_t i = 0; i < k.frame.morph_weights.size(); ++i)
    if (!k.frame.morph_weights[i].empty()) h.array(k.frame.morph_weights[i]);
  h.pod(k.width);
  h.pod(k.height);
  h.pod(k.max_depth);
  h.pod(k.seed);
  h.pod(k.spp);
  h.pod(k.relative_error);
  return h.finish_hex();
}

// ---- the cache -------------------------------------------------------------------------------

ReferenceCache::ReferenceCache(fs::path dir) : dir_(std::move(dir)) {}

fs::path ReferenceCache::path_of(const std::string& key) const { return dir_ / (key + ".ref"); }

fs::path ReferenceCache::default_dir() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg && *xdg && fs::path(xdg).is_absolute()) return fs::path(xdg) / "strata" / "references";
  const char* home = std::getenv("HOME");
  if (home && *home) return fs::path(home) / ".cache" / "strata" / "references";
  return fs::temp_directory_path() / ("strata-references-" + std::to_string(getuid()));
}

std::optional<ReferenceEntry> ReferenceCache::load(const std::string& key, std::string* why) const {
  const fs::path path = path_of(key);
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;  // no entry
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), {});
  auto corrupt = [&](const std::string& what) -> std::optional<ReferenceEntry> {
    if (why) *why = path.string() + ": " + what;
    std::error_code ec;
    fs::remove(path, ec);
    return std::nullopt;
  };
  if (bytes.size() < k_header_bytes + k_digest_bytes) return corrupt("truncated (" + std::to_string(bytes.size()) + " bytes)");
  if (std::memcmp(bytes.data(), k_magic, sizeof k_magic) != 0) return corrupt("not a strata reference file");
  size_t at = sizeof k_magic;
  if (get<uint32_t>(bytes, at) != k_format) return corrupt("unknown format version");
  if (std::string(reinterpret_cast<const char*>(bytes.data() + at), k_key_chars) != key)
    return corrupt("holds a different key");
  at += k_key_chars;
  ReferenceEntry e;
  e.image.width = get<uint32_t>(bytes, at);
  e.image.height = get<uint32_t>(bytes, at);
  e.spp = get<uint32_t>(bytes, at);
  e.batches = get<uint32_t>(bytes, at);
  e.relative_error_reached = get<uint32_t>(bytes, at) != 0;
  e.relative_error = get<double>(bytes, at);
  e.gpu_ms = get<double>(bytes, at);
  const uint64_t pixels = uint64_t(e.image.width) * e.image.height;
  if (e.image.width == 0 || e.image.height == 0 || pixels > RenderLimits::max_pixels) return corrupt("bad image size");
  const uint64_t expected = k_header_bytes + pixels * 16 + k_digest_bytes;
  if (bytes.size() != expected)
    return corrupt("size " + std::to_string(bytes.size()) + " bytes, expected " + std::to_string(expected) + " (truncated?)");
  Sha256 h;
  h.update(bytes.data(), bytes.size() - k_digest_bytes);
  const auto digest = h.finish();
  if (std::memcmp(digest.data(), bytes.data() + bytes.size() - k_digest_bytes, k_digest_bytes) != 0)
    return corrupt("checksum mismatch");
  e.image.rgba.resize(size_t(pixels) * 4);
  std::memcpy(e.image.rgba.data(), bytes.data() + at, e.image.rgba.size() * sizeof(float));
  return e;
}

void ReferenceCache::store(const std::string& key, const ReferenceEntry& e) const {
  if (key.size() != k_key_chars) throw std::invalid_argument("reference cache key must be 64 hex characters");
  if (e.image.rgba.size() != size_t(e.image.width) * e.image.height * 4) throw std::invalid_argument("reference image size mismatch");
  // Sized once and filled by memcpy (GCC 12 warns falsely about vector range inserts at -O3).
  const size_t pixel_bytes = e.image.rgba.size() * sizeof(float);
  std::vector<uint8_t> bytes(k_header_bytes + pixel_bytes + k_digest_bytes);
  size_t at = 0;
  auto put = [&](const void* p, size_t n) {
    std::memcpy(bytes.data() + at, p, n);
    at += n;
  };
  const uint32_t reached = e.relative_error_reached;
  put(k_magic, sizeof k_magic);
  put(&k_format, sizeof k_format);
  put(key.data(), k_key_chars);
  for (const uint32_t v : {e.image.width, e.image.height, e.spp, e.batches, reached}) put(&v, sizeof v);
  for (const double v : {e.relative_error, e.gpu_ms}) put(&v, sizeof v);
  put(e.image.rgba.data(), pixel_bytes);
  Sha256 h;
  h.update(bytes.data(), at);
  const auto digest = h.finish();
  put(digest.data(), digest.size());

  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) throw std::runtime_error("reference cache: cannot create " + dir_.string() + ": " + ec.message());
  // A temporary name unique to this process and write, in the same directory (same file system).
  const fs::path tmp = dir_ / (key + ".tmp." + std::to_string(getpid()) + "." + std::to_string(g_temp_counter.fetch_add(1)));
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error("reference cache: cannot create " + tmp.string() + ": " + std::strerror(errno));
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string err = std::strerror(errno);
      ::close(fd);
      fs::remove(tmp, ec);
      throw std::runtime_error("reference cache: cannot write " + tmp.string() + ": " + err);
    }
    done += size_t(n);
  }
  const bool synced = ::fsync(fd) == 0;
  const bool closed = ::close(fd) == 0;
  if (!synced || !closed) {
    fs::remove(tmp, ec);
    throw std::runtime_error("reference cache: cannot flush " + tmp.string());
  }
  fs::rename(tmp, path_of(key), ec);  // atomic: readers see the old entry or the whole new one
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw std::runtime_error("reference cache: cannot rename " + tmp.string() + " to " + path_of(key).string() + ": " + ec.message());
  }
}

}  // namespace strata::render
