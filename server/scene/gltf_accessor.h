#pragma once
// Internal to the glTF loader: reading accessors with every range checked. tinygltf checks
// JSON types but not that an accessor's bytes lie inside its buffer view and buffer; these
// readers do, before the first byte is read.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/gltf_source.h"

namespace strata::scene::gltf {

// What the reader will accept for an attribute.
enum class Components { kFloatOnly, kFloatOrNormalizedUnsigned, kFloatOrNormalized };

// Number of elements of accessor `index` (checked, no data read). `field` names the reference.
size_t accessor_count(const Source& source, int index, const std::string& field);

// Reads accessor `index` as `width`-component float vectors (width 1..4, or 16 for MAT4), converting
// normalized integers to floats as glTF defines. Throws on type mismatch, range or non-finite values.
std::vector<float> read_floats(const Source& source, int index, int width, Components allowed,
                               const std::string& field);
std::vector<glm::vec2> read_vec2(const Source& source, int index, Components allowed,
                                 const std::string& field);
std::vector<glm::vec3> read_vec3(const Source& source, int index, Components allowed,
                                 const std::string& field);
// Unsigned byte, short or int scalars (triangle indices).
std::vector<uint32_t> read_indices(const Source& source, int index, const std::string& field);
// Unsigned byte or short VEC4, not normalized: joint indices (JOINTS_n, glTF 2.0 3.7.3.3).
std::vector<glm::uvec4> read_joints(const Source& source, int index, const std::string& field);
// Float MAT4, column-major: inverse bind matrices (glTF 2.0 3.7.3.1). Not finite: refused.
std::vector<glm::mat4> read_mat4(const Source& source, int index, const std::string& field);

}  // namespace strata::scene::gltf
