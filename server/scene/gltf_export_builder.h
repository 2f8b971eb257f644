#pragma once
// Internal to export_glb: the glTF model being written and how data is appended to it, shared by
// scene/gltf_export.cpp and scene/gltf_export_skins.cpp.
#include <algorithm>
#include <initializer_list>
#include <vector>

#include <tiny_gltf.h>

#include "scene/gltf_export_textures.h"
#include "scene/scene.h"

namespace strata::scene::gltf {

class GlbBuilder {
 public:
  GlbBuilder() {
    model_.asset.version = "2.0";
    model_.asset.generator = "strata";
    model_.buffers.emplace_back();
  }

  tinygltf::Model& model() { return model_; }

  void use_extension(const char* name) {
    if (std::find(model_.extensionsUsed.begin(), model_.extensionsUsed.end(), name) ==
        model_.extensionsUsed.end()) {
      model_.extensionsUsed.emplace_back(name);
    }
  }

  // An accessor over `data` (elements of `components` components of `component_type`), in a
  // buffer view of its own. `with_bounds`: also min/max, which glTF requires for POSITION and
  // animation inputs (float data only).
  template <typename T>
  int accessor(const std::vector<T>& data, int component_type, int type, size_t components,
               int target, bool with_bounds) {
    tinygltf::Accessor a;
    a.bufferView = append_view(model_, reinterpret_cast<const uint8_t*>(data.data()), data.size() * sizeof(T));
    model_.bufferViews.back().target = target;
    a.componentType = component_type;
    a.type = type;
    a.count = data.size() * sizeof(T) /
              (components * static_cast<size_t>(tinygltf::GetComponentSizeInBytes(
                                static_cast<uint32_t>(component_type))));
    if (with_bounds && a.count > 0)
      bounds(reinterpret_cast<const float*>(data.data()), a.count, components, a);
    model_.accessors.push_back(a);
    return static_cast<int>(model_.accessors.size() - 1);
  }

 private:
  static void bounds(const float* f, size_t count, size_t components, tinygltf::Accessor& a) {
    a.minValues.assign(f, f + components);
    a.maxValues.assign(f, f + components);
    for (size_t i = 0; i < count; ++i) {
      for (size_t c = 0; c < components; ++c) {
        a.minValues[c] = std::min(a.minValues[c], static_cast<double>(f[i * components + c]));
        a.maxValues[c] = std::max(a.maxValues[c], static_cast<double>(f[i * components + c]));
      }
    }
  }

  tinygltf::Model model_;
};

constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
constexpr int kArray = TINYGLTF_TARGET_ARRAY_BUFFER;
constexpr int kElements = TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER;

inline std::vector<double> doubles(std::initializer_list<float> values) {
  return {values.begin(), values.end()};
}

// A node's rest transform: TRS where the node is animated (glTF forbids `matrix` on animated
// nodes; the exact matrix then rides in extras), else the matrix (gltf_export.cpp).
void set_rest_transform(tinygltf::Node& node, const glm::mat4& transform, bool animated);

}  // namespace strata::scene::gltf
