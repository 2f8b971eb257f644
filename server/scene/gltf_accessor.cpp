#include "scene/gltf_accessor.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace strata::scene::gltf {
namespace {

// The bytes of one accessor, located and range-checked.
struct View {
  const uint8_t* first = nullptr;  // element 0
  size_t count = 0;
  size_t stride = 0;
  int component_type = 0;
  int component_size = 0;
  int type = 0;
  bool normalized = false;
  std::string name;  // "meshes[0].primitives[1].attributes.NORMAL (accessors[7])"
};

View locate(const Source& s, int index, const std::string& field) {
  const tinygltf::Model& m = s.model;
  s.check_index(field, index, m.accessors.size(), "accessors");
  const tinygltf::Accessor& a = m.accessors[static_cast<size_t>(index)];
  const std::string name = at("accessors", static_cast<size_t>(index));
  if (a.sparse.isSparse)
    s.fail(name + ".sparse", "is not supported (sparse accessors are rejected)");
  if (a.bufferView < 0)
    s.fail(name + ".bufferView", "is missing (accessors without data are not supported)");
  s.check_index(name + ".bufferView", a.bufferView, m.bufferViews.size(), "bufferViews");
  const tinygltf::BufferView& bv = m.bufferViews[static_cast<size_t>(a.bufferView)];
  const std::string view_name = at("bufferViews", static_cast<size_t>(a.bufferView));
  s.check_index(view_name + ".buffer", bv.buffer, m.buffers.size(), "buffers");
  const std::vector<unsigned char>& data = m.buffers[static_cast<size_t>(bv.buffer)].data;

  const int component_size =
      tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
  const int components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
  if (component_size <= 0)
    s.fail(name + ".componentType", "= " + std::to_string(a.componentType) + " is unknown");
  if (components <= 0) s.fail(name + ".type", "is unknown");
  const size_t element = static_cast<size_t>(component_size) * static_cast<size_t>(components);
  const size_t stride = bv.byteStride != 0 ? bv.byteStride : element;
  if (stride < element) {
    s.fail(view_name + ".byteStride", "= " + std::to_string(stride) +
                                          " is smaller than an element of " + name + " (" +
                                          std::to_string(element) + " bytes)");
  }
  if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset) {
    s.fail(view_name, "(byteOffset " + std::to_string(bv.byteOffset) + ", byteLength " +
                          std::to_string(bv.byteLength) + ") runs past the end of its buffer (" +
                          std::to_string(data.size()) + " bytes)");
  }
  if (a.count > 0) {
    // byteOffset + (count - 1) * stride + element <= byteLength, without overflow.
    const bool fits = a.byteOffset <= bv.byteLength && element <= bv.byteLength - a.byteOffset &&
                      a.count - 1 <= (bv.byteLength - a.byteOffset - element) / stride;
    if (!fits) {
      s.fail(field + " (" + name + ")",
             "(byteOffset " + std::to_string(a.byteOffset) + ", count " + std::to_string(a.count) +
                 ", stride " + std::to_string(stride) + ") runs past the end of " + view_name +
                 " (byteLength " + std::to_string(bv.byteLength) + ")");
    }
  }
  View v;
  v.first = a.count > 0 ? data.data() + bv.byteOffset + a.byteOffset : nullptr;
  v.count = a.count;
  v.stride = stride;
  v.component_type = a.componentType;
  v.component_size = component_size;
  v.type = a.type;
  v.normalized = a.normalized;
  v.name = field + " (" + name + ")";
  return v;
}

template <typename T>
T load(const uint8_t* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  return value;
}

// One component as float, normalized integers mapped as the glTF specification defines.
float component(const View& v, const uint8_t* p) {
  switch (v.component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return load<float>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return static_cast<float>(load<uint8_t>(p)) / 255.0f;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return static_cast<float>(load<uint16_t>(p)) / 65535.0f;
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return std::max(static_cast<float>(load<int8_t>(p)) / 127.0f, -1.0f);
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return std::max(static_cast<float>(load<int16_t>(p)) / 32767.0f, -1.0f);
    default:
      return 0.0f;  // excluded by check_components
  }
}

void check_components(const Source& s, const View& v, Components allowed) {
  const bool is_float = v.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT && !v.normalized;
  const bool unsigned_norm =
      v.normalized && (v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                       v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  const bool signed_norm = v.normalized && (v.component_type == TINYGLTF_COMPONENT_TYPE_BYTE ||
                                            v.component_type == TINYGLTF_COMPONENT_TYPE_SHORT);
  const bool ok = is_float ||
                  (allowed == Components::kFloatOrNormalizedUnsigned && unsigned_norm) ||
                  (allowed == Components::kFloatOrNormalized && (unsigned_norm || signed_norm));
  if (!ok) {
    s.fail(v.name, "has componentType " + std::to_string(v.component_type) +
                       (v.normalized ? " (normalized)" : "") + ", which is not allowed here");
  }
}

int type_of_width(int width) {
  switch (width) {
    case 16:
      return TINYGLTF_TYPE_MAT4;
    case 1:
      return TINYGLTF_TYPE_SCALAR;
    case 2:
      return TINYGLTF_TYPE_VEC2;
    case 3:
      return TINYGLTF_TYPE_VEC3;
    default:
      return TINYGLTF_TYPE_VEC4;
  }
}

}  // namespace

size_t accessor_count(const Source& source, int index, const std::string& field) {
  return locate(source, index, field).count;
}

std::vector<float> read_floats(const Source& source, int index, int width, Components allowed,
                               const std::string& field) {
  const View v = locate(source, index, field);
  if (v.type != type_of_width(width)) {
    source.fail(v.name, "has the wrong type (expected " + std::to_string(width) +
                            " components per element)");
  }
  check_components(source, v, allowed);
  std::vector<float> out;
  out.reserve(v.count * static_cast<size_t>(width));
  for (size_t i = 0; i < v.count; ++i) {
    const uint8_t* element = v.first + i * v.stride;
    for (int c = 0; c < width; ++c) {
      const float value = component(v, element + c * v.component_size);
      if (!std::isfinite(value))
        source.fail(v.name, "element " + std::to_string(i) + " is not finite");
      out.push_back(value);
    }
  }
  return out;
}

std::vector<glm::vec2> read_vec2(const Source& source, int index, Components allowed,
                                 const std::string& field) {
  const std::vector<float> f = read_floats(source, index, 2, allowed, field);
  std::vector<glm::vec2> out(f.size() / 2);
  for (size_t i = 0; i < out.size(); ++i) out[i] = {f[2 * i], f[2 * i + 1]};
  return out;
}

std::vector<glm::vec3> read_vec3(const Source& source, int index, Components allowed,
                                 const std::string& field) {
  const std::vector<float> f = read_floats(source, index, 3, allowed, field);
  std::vector<glm::vec3> out(f.size() / 3);
  for (size_t i = 0; i < out.size(); ++i) out[i] = {f[3 * i], f[3 * i + 1], f[3 * i + 2]};
  return out;
}

std::vector<uint32_t> read_indices(const Source& source, int index, const std::string& field) {
  const View v = locate(source, index, field);
  if (v.type != TINYGLTF_TYPE_SCALAR || v.normalized)
    source.fail(v.name, "must be a non-normalized SCALAR");
  std::vector<uint32_t> out(v.count);
  for (size_t i = 0; i < v.count; ++i) {
    const uint8_t* p = v.first + i * v.stride;
    switch (v.component_type) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        out[i] = load<uint8_t>(p);
        break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        out[i] = load<uint16_t>(p);
        break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        out[i] = load<uint32_t>(p);
        break;
      default:
        source.fail(v.name, "has componentType " + std::to_string(v.component_type) +
                                " (indices must be unsigned byte, short or int)");
    }
  }
  return out;
}

std::vector<glm::uvec4> read_joints(const Source& source, int index, const std::string& field) {
  const View v = locate(source, index, field);
  const bool narrow = v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                      v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  if (v.type != TINYGLTF_TYPE_VEC4 || v.normalized || !narrow)
    source.fail(v.name, "must be a VEC4 of unsigned byte or unsigned short, not normalized");
  std::vector<glm::uvec4> out(v.count);
  for (size_t i = 0; i < v.count; ++i) {
    const uint8_t* p = v.first + i * v.stride;
    for (int c = 0; c < 4; ++c) {
      out[i][c] = v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE
                      ? uint32_t(load<uint8_t>(p + c))
                      : uint32_t(load<uint16_t>(p + 2 * c));
    }
  }
  return out;
}

std::vector<glm::mat4> read_mat4(const Source& source, int index, const std::string& field) {
  const std::vector<float> f = read_floats(source, index, 16, Components::kFloatOnly, field);
  std::vector<glm::mat4> out(f.size() / 16);
  for (size_t i = 0; i < out.size(); ++i) {
    for (int k = 0; k < 16; ++k) out[i][k / 4][k % 4] = f[16 * i + size_t(k)];
  }
  return out;
}

}  // namespace strata::scene::gltf
