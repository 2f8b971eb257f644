#pragma once
// Internal to the glTF loader: a parsed tinygltf model with the file's label and limits, and the
// one way loader code reports a problem (a SceneError naming file and field).
#include <string>

#include <tiny_gltf.h>

#include "scene/scene_io.h"

namespace strata::scene::gltf {

struct Source {
  const tinygltf::Model& model;
  std::string label;  // the file name (or the caller's label for in-memory data)
  LoadLimits limits;

  // Throws SceneError("<label>: <field> <what>").
  [[noreturn]] void fail(const std::string& field, const std::string& what) const;
  // Throws unless 0 <= index < count; `noun` names what is counted ("meshes").
  void check_index(const std::string& field, int index, size_t count, const char* noun) const;
};

// "array[index]", the way every field path in an error message is spelled.
std::string at(const std::string& array, size_t index);

// double -> float without undefined behaviour: out-of-range values become +-inf (and NaN stays
// NaN), which Scene::validate then reports as not finite.
float to_float(double value);

}  // namespace strata::scene::gltf
