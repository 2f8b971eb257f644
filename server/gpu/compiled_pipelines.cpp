#include "gpu/compiled_pipelines.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <string_view>

#include "embedded_shaders.h"

namespace strata::gpu {
namespace {

std::mutex g_mu;  // one reader or writer of the list at a time in this process

std::filesystem::path list_path() {
  if (const char* off = std::getenv("MESA_SHADER_CACHE_DISABLE"); off && std::string_view(off) != "false" && std::string_view(off) != "0")
    return {};
  std::filesystem::path dir;
  if (const char* d = std::getenv("MESA_SHADER_CACHE_DIR"); d && *d) dir = d;
  else if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) dir = std::filesystem::path(x) / "mesa_shader_cache";
  else if (const char* h = std::getenv("HOME"); h && *h) dir = std::filesystem::path(h) / ".cache" / "mesa_shader_cache";
  else return {};
  return dir / "strata_compiled_pipelines.txt";
}

// FNV-1a over the key, the SPIR-V words and the device name.
std::string digest(const PipelineInfo& p, const std::string& device_name) {
  uint64_t h = 1469598103934665603ull;
  auto add = [&](const void* data, size_t bytes) {
    for (size_t i = 0; i < bytes; ++i) h = (h ^ static_cast<const unsigned char*>(data)[i]) * 1099511628211ull;
  };
  const std::string key = p.key();
  add(key.data(), key.size());
  const auto words = shaders::spirv(p.shader);
  add(words.data(), words.size_bytes());
  add(device_name.data(), device_name.size());
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

std::set<std::string> read_list(const std::filesystem::path& path) {
  std::set<std::string> out;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) out.insert(line);
  return out;
}

}  // namespace

bool all_compiled(const std::vector<PipelineInfo>& pipelines, const std::string& device_name) {
  const auto path = list_path();
  if (path.empty()) return false;
  std::lock_guard lock(g_mu);
  const auto listed = read_list(path);
  for (const auto& p : pipelines)
    if (!listed.contains(digest(p, device_name))) return false;
  return true;
}

void note_compiled(const std::vector<PipelineInfo>& pipelines, const std::string& device_name) {
  const auto path = list_path();
  if (path.empty()) return;
  std::lock_guard lock(g_mu);
  const auto listed = read_list(path);
  std::error_code ec;
  std::filesystem::create_directories(path.parent_path(), ec);
  std::ofstream out(path, std::ios::app);
  for (const auto& p : pipelines)
    if (const auto d = digest(p, device_name); !listed.contains(d)) out << d << "\n";
}

}  // namespace strata::gpu
