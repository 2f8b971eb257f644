// The assimp glTF 2.0 test corpus (Debian's assimp-testmodels, under /usr/share/assimp/models/glTF2):
// every file either loads, with what it holds that strata leaves out listed, or is refused with a
// message naming the feature or the field at fault; nothing crashes. Skipped when the package is
// not installed (deploy/install-deps.sh installs it).
#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scene/scene_io.h"
#include "scene/unrendered.h"

namespace strata::scene {
namespace {

namespace fs = std::filesystem;

const fs::path kCorpus = "/usr/share/assimp/models/glTF2";

std::vector<fs::path> corpus_files() {
  std::vector<fs::path> files;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(kCorpus, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string ext = it->path().extension().string();
    if (it->is_regular_file() && (ext == ".gltf" || ext == ".glb")) files.push_back(it->path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

struct Expected {
  bool loads = true;
  std::string text;  // loads: a phrase of unrendered_features (empty: none needed); else in the error
};

Expected loads(const std::string& ignored = "") { return {true, ignored}; }
Expected refused(const std::string& error) { return {false, error}; }

// Every file of assimp-testmodels 5.2.5; files a later version adds must load or be refused too.
const std::map<std::string, Expected>& expectations() {
  static const std::map<std::string, Expected> table = {
      {"2CylinderEngine-glTF-Binary/2CylinderEngine.glb", loads()},
      {"BoxBadNormals-glTF-Binary/BoxBadNormals.glb", loads()},
      {"BoxTexcoords-glTF/boxTexcoords.gltf", loads()},
      {"BoxTextured-glTF/BoxTextured.gltf", loads()},
      {"BoxTextured-glTF-Binary/BoxTextured.glb", loads()},
      {"BoxTextured-glTF-Embedded/BoxTextured.gltf", loads()},
      {"BoxTextured-glTF-pbrSpecularGlossiness/BoxTextured.gltf",
       loads("KHR_materials_pbrSpecularGlossiness on 1 material")},
      {"BoxTextured-glTF-techniqueWebGL/BoxTextured.gltf",
       refused("extensionsRequired lists KHR_technique_webgl")},
      {"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb",
       refused("meshes[0].primitives[0].attributes.POSITION (accessors[2]) element 0 is not finite")},
      {"ClearCoat-glTF/ClearCoatTest.gltf", loads("KHR_materials_clearcoat on 6 materials")},
      {"IncorrectVertexArrays/Cube.gltf",
       refused("meshes[1].primitives[0] has 35 vertices and no indices, not a multiple of 3")},
      {"IndexOutOfRange/AllIndicesOutOfRange.gltf",
       refused("meshes[0].primitives[0].indices[0] = 65535 is out of range (24 vertices)")},
      {"IndexOutOfRange/IndexOutOfRange.gltf",
       refused("meshes[0].primitives[0].indices[0] = 255 is out of range (24 vertices)")},
      {"MissingBin/BoxTextured.gltf", refused("File not found : BoxTextured0.bin")},
      {"RecursiveNodes/RecursiveNodes.gltf", refused("scenes[0].nodes[0] = 0 is not a root node")},
      {"SchemaFailures/sceneWrongType.gltf", refused("File not found : BoxTextured0.bin")},
      {"TestNoRootNode/NoScene.gltf", refused("the scene has no geometry: the file has no nodes")},
      {"TestNoRootNode/SceneWithoutNodes.gltf",
       refused("the scene has no geometry: the file has no nodes")},
      {"cameras/Cameras.gltf", loads("orthographic camera on 1 node")},
      {"draco/2CylinderEngine.gltf",
       refused("extensionsRequired lists KHR_draco_mesh_compression (Draco-compressed meshes)")},
      {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_00.gltf",
       refused("meshes[0].primitives[0].mode = 0 (POINTS) is not supported")},
      {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_01.gltf",
       refused("meshes[0].primitives[0].mode = 1 (LINES) is not supported")},
      {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_02.gltf",
       refused("meshes[0].primitives[0].mode = 2 (LINE_LOOP) is not supported")},
      {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_03.gltf",
       refused("meshes[0].primitives[0].mode = 3 (LINE_STRIP) is not supported")},
      {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_04.gltf", loads()},
      {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_05.gltf", loads()},
      {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_06.gltf", loads()},
      {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_07.gltf",
       refused("meshes[0].primitives[0].mode = 0 (POINTS) is not supported")},
      {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_08.gltf",
       refused("meshes[0].primitives[0].mode = 1 (LINES) is not supported")},
      {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_09.gltf",
       refused("meshes[0].primitives[0].mode = 2 (LINE_LOOP) is not supported")},
      {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_10.gltf",
       refused("meshes[0].primitives[0].mode = 3 (LINE_STRIP) is not supported")},
      {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_11.gltf", loads()},
      {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_12.gltf", loads()},
      {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_13.gltf", loads()},
      {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_14.gltf", loads()},
      {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_15.gltf", loads()},
      {"glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf",
       loads("morph target TANGENT deltas on 1 mesh (not applied: the rest pose's TANGENT is used)")},
      {"issue_3269/texcoord_crash.gltf", loads()},
      {"simple_skin/simple_skin.gltf", loads()},
      {"textureTransform/TextureTransformTest.gltf", loads()},
      // tinygltf skips fields of the wrong JSON type; what is left is a valid file.
      {"wrongTypes/badArray.gltf", refused("meshes[0].primitives is empty or not an array")},
      {"wrongTypes/badExtension.gltf", loads()},
      {"wrongTypes/badNumber.gltf", loads()},
      {"wrongTypes/badObject.gltf", loads()},
      {"wrongTypes/badString.gltf", loads()},
      {"wrongTypes/badUint.gltf", loads()},
  };
  return table;
}

std::string joined(const std::vector<std::string>& items) {
  std::string s;
  for (const std::string& item : items) s += (s.empty() ? "" : " | ") + item;
  return s;
}

class GltfConformance : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::is_directory(kCorpus))
      GTEST_SKIP() << kCorpus << " is missing (apt-get install assimp-testmodels)";
  }
};

TEST_F(GltfConformance, EveryFileLoadsOrIsRefusedByName) {
  const std::vector<fs::path> files = corpus_files();
  EXPECT_GE(files.size(), expectations().size());
  for (const fs::path& file : files) {
    const std::string name = fs::relative(file, kCorpus).string();
    SCOPED_TRACE(name);
    const auto expected = expectations().find(name);
    try {
      const Scene scene = load_gltf_file(file);
      const std::string ignored = joined(unrendered_features(scene));
      if (expected == expectations().end()) continue;  // a file the table does not know: it loaded
      EXPECT_TRUE(expected->second.loads) << "loaded, expected: " << expected->second.text;
      if (expected->second.loads && !expected->second.text.empty()) {
        EXPECT_NE(ignored.find(expected->second.text), std::string::npos) << ignored;
      }
    } catch (const SceneError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(file.string() + ": ", 0), 0u) << "the message names the file: " << message;
      if (expected == expectations().end()) continue;
      EXPECT_FALSE(expected->second.loads) << message;
      if (!expected->second.loads) {
        EXPECT_NE(message.find(expected->second.text), std::string::npos) << message;
      }
    }
  }
}

TEST_F(GltfConformance, BoxTexturedLoadsWithItsTextureDecoded) {
  for (const char* file : {"BoxTextured-glTF/BoxTextured.gltf", "BoxTextured-glTF-Binary/BoxTextured.glb",
                           "BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
    SCOPED_TRACE(file);
    const Scene s = load_gltf_file(kCorpus / file);
    ASSERT_EQ(s.textures.images.size(), 1u);
    const MipLevel& top = s.textures.levels[s.textures.images[0].first_level];
    EXPECT_GT(top.width, 64u);
    const auto first = s.textures.texels.begin() + top.offset;
    const auto end = first + std::ptrdiff_t(top.width) * top.height;
    EXPECT_NE(std::find_if(first, end, [&](uint32_t t) { return t != *first; }), end) << "a uniform texture";
    EXPECT_GE(s.materials[0].base_color_texture.texture, 0);
  }
}

}  // namespace
}  // namespace strata::scene
