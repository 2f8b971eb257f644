#include "scene/gltf_read.h"

#include <cstring>
#include <fstream>
#include <limits>

#include "scene/gltf_extensions.h"

namespace strata::scene::gltf {
namespace {

namespace fs = std::filesystem;

constexpr uint32_t kGlbMagic = 0x46546C67u;  // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534Au;
constexpr uint32_t kChunkBin = 0x004E4942u;
// tinygltf turns `extras` and `extensions` into Values recursively; deeper JSON could exhaust
// the stack. Real glTF files nest less than 16 levels.
constexpr int kMaxJsonDepth = 128;
constexpr size_t kMaxQuotedError = 400;  // tinygltf may quote a whole data: URI

[[noreturn]] void fail(const std::string& label, const std::string& what) {
  throw SceneError(label + ": " + what);
}

uint32_t read_u32(std::span<const uint8_t> bytes, size_t offset) {
  uint32_t value;
  std::memcpy(&value, bytes.data() + offset, 4);
  return value;  // glTF is little-endian, as is every platform strata builds for
}

void check_json_depth(std::span<const uint8_t> json, const std::string& label) {
  int depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < json.size(); ++i) {
    const uint8_t c = json[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '{' || c == '[') {
      if (++depth > kMaxJsonDepth)
        fail(label, "JSON nests deeper than " + std::to_string(kMaxJsonDepth) + " levels");
    } else if (c == '}' || c == ']') {
      --depth;
    }
  }
}

// The JSON chunk of a .glb, after checking the container against the spec's layout.
std::span<const uint8_t> glb_json_chunk(std::span<const uint8_t> bytes, const std::string& label) {
  if (bytes.size() < 20)
    fail(label, "truncated .glb: " + std::to_string(bytes.size()) + " bytes, the header needs 20");
  if (read_u32(bytes, 4) != 2)
    fail(label, ".glb version " + std::to_string(read_u32(bytes, 4)) + " is not 2");
  const uint64_t length = read_u32(bytes, 8);
  if (length > bytes.size()) {
    fail(label, "truncated .glb: the header says " + std::to_string(length) + " bytes, only " +
                    std::to_string(bytes.size()) + " are there");
  }
  const uint64_t json_length = read_u32(bytes, 12);
  if (read_u32(bytes, 16) != kChunkJson) fail(label, ".glb: the first chunk is not JSON");
  if (20 + json_length > length)
    fail(label, "truncated .glb: the JSON chunk runs past the end of the file");
  const uint64_t bin_start = 20 + ((json_length + 3) & ~uint64_t{3});
  if (bin_start + 8 <= length) {
    const uint64_t bin_length = read_u32(bytes, bin_start);
    if (read_u32(bytes, bin_start + 4) == kChunkBin && bin_start + 8 + bin_length > length) {
      fail(label, "truncated .glb: the BIN chunk runs past the end of the file");
    }
  }
  return bytes.subspan(20, json_length);
}

// Confines tinygltf's file access (FsCallbacks) to one directory and a byte budget.
struct FileGuard {
  std::optional<fs::path> root;  // canonical; nullopt: no external files at all
  std::string root_prefix;       // root + "/", how tinygltf spells paths it built from root
  uint64_t budget = 0;
  std::string violation;  // the first refused access, reported instead of tinygltf's error
};

bool inside_root(const FileGuard& guard, const std::string& path) {
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(fs::path(path), ec);
  if (ec) return false;
  auto r = guard.root->begin();
  auto p = resolved.begin();
  for (; r != guard.root->end(); ++r, ++p) {
    if (p == resolved.end() || *p != *r) return false;
  }
  return true;
}

bool guarded_exists(const std::string& path, void* user) {
  auto& guard = *static_cast<FileGuard*>(user);
  if (!guard.root) {
    if (guard.violation.empty()) {
      guard.violation = "URI '" + path +
                        "' refers to an external file; in-memory glTF may only use data: URIs and "
                        "the .glb BIN chunk";
    }
    return false;
  }
  // tinygltf also tries each URI relative to the working directory; those attempts are refused
  // quietly.
  if (path.rfind(guard.root_prefix, 0) != 0) return false;
  if (!inside_root(guard, path)) {
    if (guard.violation.empty()) {
      guard.violation = "URI '" + path.substr(guard.root_prefix.size()) +
                        "' escapes the directory " + guard.root->string();
    }
    return false;
  }
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

std::string identity_path(const std::string& path, void*) {
  return path;
}

bool guarded_read(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                  void* user) {
  auto& guard = *static_cast<FileGuard*>(user);
  std::error_code ec;
  if (!guard.root || path.rfind(guard.root_prefix, 0) != 0 || !inside_root(guard, path) ||
      !fs::is_regular_file(path, ec)) {
    *err = "refused";
    return false;
  }
  const uint64_t size = fs::file_size(path, ec);
  if (ec || size > guard.budget) {
    if (guard.violation.empty()) {
      guard.violation = "external file '" + path + "' would exceed LoadLimits::max_file_bytes";
    }
    *err = "too big";
    return false;
  }
  guard.budget -= size;
  std::ifstream in(path, std::ios::binary);
  out->resize(size);
  if (!in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size))) {
    *err = "read error";
    return false;
  }
  return true;
}

bool refuse_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  *err = "writing is disabled";
  return false;
}

// Keeps the encoded bytes of each image given by URI (data: or a file), for gltf_textures.cpp to
// decode the ones materials use. Images in a bufferView are read from it there, range-checked:
// tinygltf hands this callback a pointer into the buffer without checking the view's extent.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  if (image->bufferView == -1 && bytes != nullptr && size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

}  // namespace

std::vector<uint8_t> read_file(const fs::path& path, const LoadLimits& limits) {
  const std::string label = path.string();
  std::error_code ec;
  if (!fs::exists(path, ec)) fail(label, "cannot read the file: it does not exist");
  if (!fs::is_regular_file(path, ec)) fail(label, "cannot read the file: not a regular file");
  const uint64_t size = fs::file_size(path, ec);
  if (ec) fail(label, "cannot read the file: " + ec.message());
  if (size > limits.max_file_bytes) {
    fail(label, "file is " + std::to_string(size) + " bytes, over LoadLimits::max_file_bytes (" +
                    std::to_string(limits.max_file_bytes) + ")");
  }
  std::ifstream in(path, std::ios::binary);
  std::vector<uint8_t> bytes(size);
  if (!in || !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size))) {
    fail(label, "cannot read the file");
  }
  return bytes;
}

tinygltf::Model parse_model(std::span<const uint8_t> bytes, const std::string& label,
                            const std::optional<fs::path>& directory, uint64_t budget) {
  if (bytes.empty()) fail(label, "file is empty");
  if (bytes.size() > std::numeric_limits<uint32_t>::max()) fail(label, "file is 4 GiB or more");
  const bool binary = bytes.size() >= 4 && read_u32(bytes, 0) == kGlbMagic;
  std::span<const uint8_t> json = binary ? glb_json_chunk(bytes, label) : bytes;
  if (!binary) {
    size_t first = 0;
    while (first < json.size() && std::strchr(" \t\r\n", json[first]) != nullptr) ++first;
    if (first == json.size() || json[first] != '{')
      fail(label, "is not a glTF file (neither a .glb header nor a JSON object)");
  }
  check_json_depth(json, label);
  refuse_required_extensions(json, label);

  FileGuard guard;
  guard.budget = budget;
  if (directory) {
    std::error_code ec;
    guard.root = fs::weakly_canonical(*directory, ec);
    if (ec) fail(label, "cannot resolve the directory " + directory->string());
    // tinygltf joins base_dir and URI with a '/' unless base_dir already ends with one.
    const std::string root = guard.root->string();
    guard.root_prefix = root.back() == '/' ? root : root + "/";
  }
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&guarded_exists, &identity_path, &guarded_read, &refuse_write, &guard});
  loader.SetImageLoader(&keep_encoded_image, nullptr);
  tinygltf::Model model;
  std::string error, warning;
  const std::string base_dir = guard.root ? guard.root->string() : std::string();
  const auto size = static_cast<unsigned int>(bytes.size());
  bool ok = false;
  try {
    ok = binary
             ? loader.LoadBinaryFromMemory(&model, &error, &warning, bytes.data(), size, base_dir)
             : loader.LoadASCIIFromString(&model, &error, &warning,
                                          reinterpret_cast<const char*>(bytes.data()), size,
                                          base_dir);
  } catch (const std::exception& e) {  // e.g. bad_alloc for an absurd byteLength
    fail(label, std::string("invalid glTF: ") + e.what());
  }
  if (!guard.violation.empty()) fail(label, guard.violation);
  if (!ok) {
    if (error.empty()) error = warning;  // e.g. "Image data is empty for image[0]"
    if (error.size() > kMaxQuotedError) error = error.substr(0, kMaxQuotedError) + "...";
    while (!error.empty() && (error.back() == '\n' || error.back() == ' ')) error.pop_back();
    fail(label, "invalid glTF: " + (error.empty() ? std::string("tinygltf rejected it") : error));
  }
  return model;
}

}  // namespace strata::scene::gltf
