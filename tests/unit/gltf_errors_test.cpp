// Malformed glTF input: every case is a SceneError whose message names the file and the field,
// never a crash or an unchecked read.
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "gltf_test_builder.h"
#include "scene/scene_io.h"

namespace strata::scene {
namespace {

using nlohmann::json;
using testing::TestGltf;

std::string error_of(const std::vector<uint8_t>& bytes, const LoadLimits& limits = {}) {
  try {
    load_glb_bytes(bytes, "bad.gltf", limits);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(loaded without error)";
}

std::string file_error_of(const std::filesystem::path& path, const LoadLimits& limits = {}) {
  try {
    load_gltf_file(path, limits);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(loaded without error)";
}

::testing::AssertionResult contains(const std::string& message, const std::string& expected) {
  if (message.find(expected) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "expected '" << expected << "' in '" << message << "'";
}

std::vector<uint8_t> bytes_of(const std::string& s) {
  return {s.begin(), s.end()};
}

// A valid one-quad file to break in one place.
TestGltf quad_file() {
  TestGltf g;
  g.node({{"mesh", g.quad_mesh()}});
  return g;
}

TEST(GltfErrors, NotGltfEmptyAndBadJson) {
  EXPECT_TRUE(contains(error_of(bytes_of("hello, world")), "bad.gltf: is not a glTF file"));
  EXPECT_TRUE(contains(error_of({}), "bad.gltf: file is empty"));
  EXPECT_TRUE(contains(error_of(bytes_of("{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [")),
                       "invalid glTF"));
  EXPECT_TRUE(contains(error_of(bytes_of("{\"asset\": {\"version\": \"2.0\"}, \"extras\": " +
                                         std::string(5000, '[') + std::string(5000, ']') + "}")),
                       "nests deeper"));
}

TEST(GltfErrors, TruncatedGlb) {
  std::vector<uint8_t> glb = export_glb(builtin_scene("cornell"));
  glb.resize(glb.size() / 2);
  EXPECT_TRUE(contains(error_of(glb), "truncated .glb"));
  glb.resize(10);
  EXPECT_TRUE(contains(error_of(glb), "truncated .glb"));
}

TEST(GltfErrors, AccessorAndBufferViewOutOfRange) {
  TestGltf g = quad_file();
  g.doc["accessors"][0]["count"] = 100;
  EXPECT_TRUE(contains(
      error_of(g.text_bytes()),
      "(accessors[0]) (byteOffset 0, count 100, stride 12) runs past the end of bufferViews[0]"));
  g = quad_file();
  g.doc["accessors"][0]["byteOffset"] = 1u << 30;
  EXPECT_TRUE(contains(error_of(g.text_bytes()), "runs past the end"));
  g = quad_file();
  g.doc["bufferViews"][1]["byteLength"] = 4096;
  EXPECT_TRUE(
      contains(error_of(g.text_bytes()),
               "bufferViews[1] (byteOffset 48, byteLength 4096) runs past the end of its buffer"));
  g = quad_file();
  g.doc["accessors"][0]["bufferView"] = 9;
  EXPECT_TRUE(contains(error_of(g.text_bytes()),
                       "accessors[0].bufferView = 9 is out of range (2 bufferViews)"));
  g = quad_file();
  g.doc["accessors"][0]["type"] = "VEC2";
  EXPECT_TRUE(
      contains(error_of(g.text_bytes()), "attributes.POSITION (accessors[0]) has the wrong type"));
  g = quad_file();
  g.doc["accessors"][0]["sparse"] = {{"count", 1},
                                     {"indices", {{"bufferView", 1}, {"componentType", 5125}}},
                                     {"values", {{"bufferView", 0}}}};
  EXPECT_TRUE(contains(error_of(g.text_bytes()), "accessors[0].sparse is not supported"));
}

TEST(GltfErrors, IndexOutOfRangeAndBadPrimitives) {
  TestGltf g;
  g.node({{"mesh", g.mesh({{"attributes", {{"POSITION", g.quad_positions()}}},
                           {"indices", g.u32({0, 1, 7})}})}});
  EXPECT_TRUE(contains(error_of(g.text_bytes()),
                       "meshes[0].primitives[0].indices[2] = 7 is out of range (4 vertices)"));

  g = TestGltf();
  g.node({{"mesh", g.mesh({{"attributes", json::object()}, {"indices", g.quad_indices()}})}});
  EXPECT_TRUE(
      contains(error_of(g.text_bytes()), "meshes[0].primitives[0].attributes.POSITION is missing"));

  g = TestGltf();
  g.node(
      {{"mesh",
        g.mesh({{"attributes",
                 {{"POSITION", g.floats({0, 0, 0, 1, std::nanf(""), 0, 0, 1, 0}, "VEC3", 3)}}}})}});
  EXPECT_TRUE(contains(error_of(g.text_bytes()),
                       "attributes.POSITION (accessors[0]) element 1 is not finite"));

  g = quad_file();
  g.doc["meshes"][0]["primitives"][0]["mode"] = 1;
  EXPECT_TRUE(
      contains(error_of(g.text_bytes()), "meshes[0].primitives[0].mode = 1 (LINES) is not supported"));

  g = quad_file();
  g.doc["meshes"][0]["primitives"][0]["material"] = 3;
  EXPECT_TRUE(contains(error_of(g.text_bytes()),
                       "meshes[0].primitives[0].material = 3 is out of range (0 materials)"));

  g = quad_file();
  g.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] =
      g.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
  EXPECT_TRUE(
      contains(error_of(g.text_bytes()), "attributes.NORMAL has 3 elements, POSITION has 4"));

  g = quad_file();
  g.doc["nodes"][0]["mesh"] = 5;
  EXPECT_TRUE(contains(error_of(g.text_bytes()), "nodes[0].mesh = 5 is out of range (1 meshes)"));
}

TEST(GltfErrors, HierarchyAndExtensions) {
  TestGltf g = quad_file();
  g.doc["nodes"][0]["extensions"] = {{"MSFT_lod", {{"ids", {7}}}}};
  EXPECT_TRUE(contains(error_of(g.text_bytes()),
                       "nodes[0].extensions.MSFT_lod.ids[0] = 7 is out of range (1 nodes)"));

  g = quad_file();
  g.node({{"children", {0}}});
  g.node({{"children", {0}}});
  EXPECT_TRUE(contains(error_of(g.text_bytes()), "nodes[2].children[0] = 0 already has a parent"));

  g = quad_file();
  g.scene({0});
  g.doc["scene"] = 3;
  EXPECT_TRUE(contains(error_of(g.text_bytes()), "scene = 3 is out of range (1 scenes)"));

  g = quad_file();
  g.doc["materials"] =
      json::array({{{"pbrMetallicRoughness", {{"baseColorFactor", {1e39, 0, 0, 1}}}}}});
  g.doc["meshes"][0]["primitives"][0]["material"] = 0;
  EXPECT_TRUE(
      contains(error_of(g.text_bytes()), "bad.gltf: materials[0].base_color is not finite"));
}

TEST(GltfErrors, Animations) {
  TestGltf g = quad_file();
  const int times = g.floats({0.0f, 1.0f}, "SCALAR", 1);
  const int values = g.floats({0, 0, 0, 1, 0, 0}, "VEC3", 3);
  auto with_animation = [&](const json& sampler, int node) {
    TestGltf copy = g;
    copy.doc["animations"] = json::array(
        {{{"samplers", {sampler}},
          {"channels",
           {{{"sampler", 0}, {"target", {{"node", node}, {"path", "translation"}}}}}}}});
    return copy.text_bytes();
  };
  EXPECT_TRUE(
      contains(error_of(with_animation(
                   {{"input", times}, {"output", values}, {"interpolation", "CUBICSPLINE"}}, 0)),
               "animations[0].samplers[0].interpolation = CUBICSPLINE is not supported"));
  EXPECT_TRUE(contains(error_of(with_animation({{"input", times}, {"output", values}}, 4)),
                       "animations[0].channels[0].target.node = 4 is out of range"));
  EXPECT_TRUE(contains(error_of(with_animation({{"input", times}, {"output", times}}, 0)),
                       "samplers[0].output"));
}

TEST(GltfErrors, LoadLimits) {
  TestGltf g = quad_file();
  g.node({{"mesh", 0}});
  LoadLimits limits;
  limits.max_triangles = 1;
  EXPECT_TRUE(contains(error_of(g.text_bytes(), limits), "over LoadLimits::max_triangles (1)"));
  limits = LoadLimits{};
  limits.max_instances = 1;
  EXPECT_TRUE(contains(error_of(g.text_bytes(), limits), "over LoadLimits::max_instances (1)"));
  limits = LoadLimits{};
  limits.max_file_bytes = 64;
  EXPECT_TRUE(contains(error_of(g.text_bytes(), limits), "max_file_bytes"));
  limits = LoadLimits{};
  limits.max_lod_levels = 2;
  EXPECT_TRUE(contains(error_of(export_glb(builtin_scene("chess")), limits),
                       "over LoadLimits::max_lod_levels (2)"));
}

class GltfFileErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / "strata_gltf_errors" / "a" / "b";
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_.parent_path().parent_path()); }
  std::filesystem::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }
  std::filesystem::path dir_;
};

TEST_F(GltfFileErrors, UnreadableEmptyAndTooBig) {
  EXPECT_TRUE(contains(file_error_of(dir_ / "nope.glb"),
                       "nope.glb: cannot read the file: it does not exist"));
  EXPECT_TRUE(contains(file_error_of(dir_), "not a regular file"));
  EXPECT_TRUE(contains(file_error_of(write("empty.gltf", "")), "empty.gltf: file is empty"));
  LoadLimits limits;
  limits.max_file_bytes = 16;
  EXPECT_TRUE(contains(file_error_of(write("big.gltf", quad_file().text()), limits),
                       "over LoadLimits::max_file_bytes (16)"));
}

TEST_F(GltfFileErrors, ExternalUrisStayInTheFilesDirectory) {
  TestGltf g = quad_file();
  json doc = g.doc;
  // A parent directory holding a real file, so the escape is not just "file not found".
  std::ofstream(dir_.parent_path() / "secret.bin", std::ios::binary)
      << std::string(g.bin.size(), 'x');
  for (const std::string uri : {"../../etc/passwd", "../secret.bin", "..%2Fsecret.bin"}) {
    doc["buffers"] = json::array({{{"byteLength", g.bin.size()}, {"uri", uri}}});
    EXPECT_TRUE(contains(file_error_of(write("escape.gltf", doc.dump())), "escapes the directory"))
        << uri;
  }
  doc["buffers"] = json::array({{{"byteLength", g.bin.size()}, {"uri", "missing.bin"}}});
  EXPECT_TRUE(contains(file_error_of(write("missing.gltf", doc.dump())), "missing.bin"));
  // In memory there is no directory at all.
  doc["buffers"] = json::array({{{"byteLength", g.bin.size()}, {"uri", "data.bin"}}});
  EXPECT_TRUE(contains(error_of(bytes_of(doc.dump())), "refers to an external file"));
}

// Random byte corruption of a real .glb (JSON and binary chunk alike): each load either succeeds
// or throws SceneError. Run under the asan preset this also proves no read goes out of bounds.
TEST(GltfErrors, RandomCorruptionNeverCrashes) {
  const std::vector<uint8_t> original = export_glb(builtin_scene("overlap-uv"));
  std::mt19937 rng(1234);
  std::uniform_int_distribution<size_t> position(0, original.size() - 1);
  std::uniform_int_distribution<int> byte(0, 255);
  size_t rejected = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<uint8_t> bytes = original;
    // Early trials hit the JSON chunk (where structure lives), later ones anywhere.
    std::uniform_int_distribution<size_t> json_position(20, 20 + 2000);
    for (int k = 0; k < 1 + trial % 4; ++k) {
      bytes[trial < 200 ? json_position(rng) : position(rng)] = static_cast<uint8_t>(byte(rng));
    }
    try {
      load_glb_bytes(bytes, "corrupt.glb");
    } catch (const SceneError&) {
      ++rejected;
    }
  }
  EXPECT_GT(rejected, 0u);
}

// Hand-made malformed files kept in tests/data/gltf.
TEST(GltfErrorFiles, EachIsRejectedWithItsReason) {
  const std::filesystem::path data = std::filesystem::path(STRATA_TEST_DATA_DIR) / "gltf";
  const std::pair<const char*, const char*> cases[] = {
      {"not_gltf.gltf", "is not a glTF file"},
      {"bad_json.gltf", "invalid glTF"},
      {"escape_uri.gltf", "escapes the directory"},
      {"bad_version.glb", ".glb version 1 is not 2"},
      {"glb_length_lies.glb", "truncated .glb"},
      {"index_out_of_range.gltf", "indices[2] = 9 is out of range (3 vertices)"},
  };
  for (const auto& [file, expected] : cases) {
    EXPECT_TRUE(contains(file_error_of(data / file), expected)) << file;
  }
}

}  // namespace
}  // namespace strata::scene
