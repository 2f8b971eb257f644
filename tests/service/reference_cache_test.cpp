// The reference cache (render/reference_cache.h) on its own, no device: the key follows every
// field of the frame state and settings, entries round-trip, corrupt and truncated entries read
// as absent, and writes are atomic (no partial entry, no temporary file left, concurrent writers).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <thread>

#include <glm/gtc/matrix_transform.hpp>

#include "harness.h"
#include "render/reference.h"
#include "render/reference_cache.h"
#include "scene/scene_io.h"

namespace strata::test {
namespace {

namespace fs = std::filesystem;
using render::ReferenceCache;
using render::ReferenceEntry;
using render::ReferenceKey;

ReferenceKey base_key() {
  static const scene::Scene carousel = scene::builtin_scene("carousel");
  ReferenceKey k;
  k.scene_hash = render::scene_content_hash(carousel);
  k.frame = carousel.frame_state(3);
  k.width = 16;
  k.height = 12;
  k.max_depth = 16;
  k.seed = 7;
  k.spp = 64;
  return k;
}

ReferenceEntry entry(uint32_t w, uint32_t h, float base) {
  ReferenceEntry e;
  e.image.width = w;
  e.image.height = h;
  e.image.rgba.resize(size_t(w) * h * 4);
  for (size_t i = 0; i < e.image.rgba.size(); ++i) e.image.rgba[i] = base + float(i) * 0.25f;
  e.spp = 64;
  e.batches = 16;
  e.relative_error = 0.0123;
  e.relative_error_reached = true;
  e.gpu_ms = 42.5;
  return e;
}

std::vector<fs::path> files_in(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path());
  return out;
}

TEST(ReferenceCacheTest, KeyChangesWithEveryFieldOfFrameStateAndSettings) {
  const ReferenceKey k = base_key();
  ASSERT_GE(k.frame.transforms.size(), 2u);
  const std::string base = render::reference_cache_key(k);
  EXPECT_EQ(base.size(), 64u);
  EXPECT_EQ(render::reference_cache_key(base_key()), base) << "the key is deterministic";

  std::vector<std::pair<std::string, std::function<void(ReferenceKey&)>>> edits = {
      {"scene hash", [](ReferenceKey& x) { x.scene_hash = render::scene_content_hash(scene::builtin_scene("cornell")); }},
      {"camera.position", [](ReferenceKey& x) { x.frame.camera.position.x += 1e-4f; }},
      {"camera.orientation", [](ReferenceKey& x) { x.frame.camera.orientation = glm::normalize(x.frame.camera.orientation * glm::quat(0.999f, 0.01f, 0, 0)); }},
      {"camera.yfov", [](ReferenceKey& x) { x.frame.camera.yfov += 0.01f; }},
      {"camera.aperture", [](ReferenceKey& x) { x.frame.camera.aperture = 0.01f; }},
      {"camera.focus_distance", [](ReferenceKey& x) { x.frame.camera.focus_distance += 0.5f; }},
      {"camera.shutter", [](ReferenceKey& x) { x.frame.camera.shutter = 0.5f; }},
      {"camera_open", [](ReferenceKey& x) { x.frame.camera_open = x.frame.camera; }},
      {"camera_open.position", [](ReferenceKey& x) {
         x.frame.camera_open = x.frame.camera;
         x.frame.camera_open->position.x -= 1e-3f;
       }},
      {"camera_open.orientation", [](ReferenceKey& x) {
         x.frame.camera_open = x.frame.camera;
         x.frame.camera_open->orientation = glm::normalize(x.frame.camera.orientation * glm::quat(0.999f, 0, 0.01f, 0));
       }},
      {"transform of instance 0", [](ReferenceKey& x) { x.frame.transforms[0][3][1] += 1e-3f; }},
      {"transform of the last instance",
       [](ReferenceKey& x) { x.frame.transforms.back() = glm::scale(x.frame.transforms.back(), glm::vec3(1.001f)); }},
      {"LoD level", [](ReferenceKey& x) { x.frame.lods[0] += 1; }},
      {"width", [](ReferenceKey& x) { x.width += 1; }},
      {"height", [](ReferenceKey& x) { x.height += 1; }},
      {"max_depth", [](ReferenceKey& x) { x.max_depth += 1; }},
      {"seed", [](ReferenceKey& x) { x.seed += 1; }},
      {"spp", [](ReferenceKey& x) { x.spp += 1; }},
      {"relative_error", [](ReferenceKey& x) { x.relative_error = 0.01f; }},
  };
  std::set<std::string> keys = {base};
  for (const auto& [what, edit] : edits) {
    ReferenceKey changed = base_key();
    edit(changed);
    const std::string key = render::reference_cache_key(changed);
    EXPECT_NE(key, base) << what << " does not change the key";
    keys.insert(key);
  }
  EXPECT_EQ(keys.size(), edits.size() + 1) << "two different edits gave the same key";

  // The animation's frames are different states; the same frame is the same state.
  ReferenceKey other = base_key();
  other.frame = scene::builtin_scene("carousel").frame_state(4);
  EXPECT_NE(render::reference_cache_key(other), base);
}

TEST(ReferenceCacheTest, SceneContentHashFollowsContentNotNames) {
  const scene::Scene a = scene::builtin_scene("cornell");
  scene::Scene b = scene::builtin_scene("cornell");
  EXPECT_EQ(render::scene_content_hash(a), render::scene_content_hash(b));
  b.name = "renamed";
  EXPECT_EQ(render::scene_content_hash(a), render::scene_content_hash(b)) << "names do not change the image";
  b.materials[0].base_color.r += 0.01f;
  EXPECT_NE(render::scene_content_hash(a), render::scene_content_hash(b));
  scene::Scene c = scene::builtin_scene("cornell");
  c.meshes[0].primitives[0].positions[0].x += 1e-3f;
  EXPECT_NE(render::scene_content_hash(a), render::scene_content_hash(c));
  scene::Scene d = scene::builtin_scene("cornell");
  d.environment.radiance += glm::vec3(0.1f);
  EXPECT_NE(render::scene_content_hash(a), render::scene_content_hash(d));
  EXPECT_NE(render::scene_content_hash(a), render::scene_content_hash(scene::builtin_scene("carousel")));
}

TEST(ReferenceCacheTest, EntriesRoundTripAndAbsentKeysMiss) {
  TempDir dir;
  const ReferenceCache cache(dir.path / "nested" / "references");  // created on demand
  const std::string key = render::reference_cache_key(base_key());
  EXPECT_FALSE(cache.load(key).has_value());
  const ReferenceEntry e = entry(16, 12, 0.5f);
  cache.store(key, e);
  const auto back = cache.load(key);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->image.width, 16u);
  EXPECT_EQ(back->image.height, 12u);
  EXPECT_EQ(back->image.rgba, e.image.rgba);
  EXPECT_EQ(back->spp, e.spp);
  EXPECT_EQ(back->batches, e.batches);
  EXPECT_EQ(back->relative_error, e.relative_error);
  EXPECT_EQ(back->relative_error_reached, e.relative_error_reached);
  EXPECT_EQ(back->gpu_ms, e.gpu_ms);
  EXPECT_EQ(files_in(cache.dir()), std::vector<fs::path>{cache.path_of(key)}) << "no temporary file is left";
}

TEST(ReferenceCacheTest, CorruptOrTruncatedEntriesReadAsAbsentAndAreRemoved) {
  TempDir dir;
  const ReferenceCache cache(dir.path);
  const std::string key = render::reference_cache_key(base_key());
  const auto write_and_damage = [&](const std::function<void(std::string&)>& damage) {
    cache.store(key, entry(16, 12, 1.0f));
    std::string bytes;
    {
      std::ifstream in(cache.path_of(key), std::ios::binary);
      bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    damage(bytes);
    std::ofstream(cache.path_of(key), std::ios::binary | std::ios::trunc) << bytes;
  };
  struct Case {
    std::string what, message;
    std::function<void(std::string&)> damage;
  };
  const std::vector<Case> cases = {
      {"a flipped pixel bit", "checksum mismatch", [](std::string& b) { b[b.size() / 2] = char(b[b.size() / 2] ^ 0x10); }},
      {"a flipped checksum bit", "checksum mismatch", [](std::string& b) { b.back() = char(b.back() ^ 1); }},
      {"truncated (interrupted copy)", "truncated", [](std::string& b) { b.resize(b.size() - 100); }},
      {"truncated to the header", "truncated", [](std::string& b) { b.resize(40); }},
      {"empty", "truncated", [](std::string& b) { b.clear(); }},
      {"wrong magic", "not a strata reference file", [](std::string& b) { b[0] = 'X'; }},
      {"another key's entry", "different key", [](std::string& b) { b[13] = b[13] == 'a' ? 'b' : 'a'; }},
  };
  for (const auto& c : cases) {
    write_and_damage(c.damage);
    std::string why;
    EXPECT_FALSE(cache.load(key, &why).has_value()) << c.what;
    EXPECT_NE(why.find(c.message), std::string::npos) << c.what << ": " << why;
    EXPECT_FALSE(fs::exists(cache.path_of(key))) << c.what << ": the corrupt entry was not removed";
  }
  // A fresh store after the corrupt one is good again.
  cache.store(key, entry(16, 12, 1.0f));
  EXPECT_TRUE(cache.load(key).has_value());
}

TEST(ReferenceCacheTest, WritesAreAtomic) {
  TempDir dir;
  const ReferenceCache cache(dir.path);
  const std::string key = render::reference_cache_key(base_key());
  // An interrupted writer leaves at most its temporary file: it is never read as the entry.
  std::ofstream(dir.path / (key + ".tmp.99999.0"), std::ios::binary) << "partial";
  EXPECT_FALSE(cache.load(key).has_value());
  // Concurrent writers of the same key (two stratad processes, say): the entry is one of theirs,
  // whole, at every moment a reader looks.
  std::atomic<bool> stop{false};
  std::atomic<int> reads{0}, bad_reads{0};
  std::thread reader([&] {
    while (!stop.load()) {
      if (auto e = cache.load(key)) {
        ++reads;
        if (e->image.rgba.size() != 64u * 48u * 4u || (e->image.rgba[0] != 1.0f && e->image.rgba[0] != 2.0f)) ++bad_reads;
      }
    }
  });
  std::vector<std::thread> writers;
  for (int w = 0; w < 4; ++w)
    writers.emplace_back([&, w] {
      for (int i = 0; i < 20; ++i) cache.store(key, entry(64, 48, w % 2 ? 1.0f : 2.0f));
    });
  for (auto& t : writers) t.join();
  stop = true;
  reader.join();
  EXPECT_EQ(bad_reads.load(), 0);
  EXPECT_GT(reads.load(), 0);
  const auto final_entry = cache.load(key);
  ASSERT_TRUE(final_entry.has_value());
  EXPECT_EQ(final_entry->image.width, 64u);
  // Only the entry and the interrupted writer's leftover: every write's temporary file was renamed.
  EXPECT_EQ(files_in(dir.path).size(), 2u);
}

TEST(ReferenceCacheTest, DefaultDirectoryFollowsXdgCacheHome) {
  const char* old = std::getenv("XDG_CACHE_HOME");
  const std::string saved = old ? old : "";
  setenv("XDG_CACHE_HOME", "/var/tmp/xdg-test", 1);
  EXPECT_EQ(ReferenceCache::default_dir(), fs::path("/var/tmp/xdg-test/strata/references"));
  setenv("XDG_CACHE_HOME", "relative/ignored", 1);  // the XDG spec: relative paths are invalid
  EXPECT_NE(ReferenceCache::default_dir().string().find("strata"), std::string::npos);
  EXPECT_TRUE(ReferenceCache::default_dir().is_absolute());
  if (old) setenv("XDG_CACHE_HOME", saved.c_str(), 1);
  else unsetenv("XDG_CACHE_HOME");
}

TEST(ReferenceCacheTest, BatchesAddUpToTheTargetAndSeedsDiffer) {
  for (uint32_t spp : {1u, 2u, 16u, 32u, 37u, 1000u, 1024u, 65536u}) {
    const uint32_t b = render::reference_batch_spp(spp);
    EXPECT_GE(b, 1u);
    EXPECT_LE(b, 32u);
    EXPECT_LE((spp + b - 1) / b * b - spp, b - 1) << spp;  // whole batches overshoot by less than one
  }
  EXPECT_EQ(render::reference_batch_spp(32), 2u);
  EXPECT_EQ(render::reference_batch_spp(1000) * 40, 1000u);
  for (uint32_t seed : {0u, 1u, 5u, 1234u}) EXPECT_NE(render::reference_seed(seed), seed);
  EXPECT_NE(render::reference_seed(0), render::reference_seed(1));
}

}  // namespace
}  // namespace strata::test
