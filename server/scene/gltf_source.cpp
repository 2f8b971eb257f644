#include "scene/gltf_source.h"

#include <limits>

namespace strata::scene::gltf {

void Source::fail(const std::string& field, const std::string& what) const {
  throw SceneError(label + ": " + field + " " + what);
}

void Source::check_index(const std::string& field, int index, size_t count,
                         const char* noun) const {
  if (index < 0 || static_cast<size_t>(index) >= count) {
    fail(field, "= " + std::to_string(index) + " is out of range (" + std::to_string(count) + " " +
                    noun + ")");
  }
}

std::string at(const std::string& array, size_t index) {
  return array + "[" + std::to_string(index) + "]";
}

float to_float(double value) {
  constexpr double kMax = static_cast<double>(std::numeric_limits<float>::max());
  if (value > kMax) return std::numeric_limits<float>::infinity();
  if (value < -kMax) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(value);  // NaN converts to NaN
}

}  // namespace strata::scene::gltf
