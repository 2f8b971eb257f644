#include "ops_util.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace strata::test {

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

std::string tool_path(const char* env, const std::string& fallback) {
  const char* v = std::getenv(env);
  return v && *v ? v : fallback;
}

namespace {
bool wants(const std::vector<std::string>& args, const std::string& flag) {
  for (const auto& a : args)
    if (a == flag) return true;
  return false;
}
}  // namespace

OpsDaemon::OpsDaemon(const std::vector<std::string>& args) : daemon_(args) {
  // The addresses are printed right after the port file is written; wait for the lines.
  const bool metrics = wants(args, "--metrics-listen"), http = wants(args, "--http");
  const bool ok = wait_until([&] {
    const std::string out = daemon_.process().output();
    if (metrics) metrics_ = address_after(out, "metrics on");
    if (http) http_ = address_after(out, "dashboard on");
    return (!metrics || !metrics_.empty()) && (!http || !http_.empty());
  }, 10s);
  if (!ok) throw std::runtime_error("stratad did not print its ops addresses:\n" + daemon_.process().output());
}

double sample_value(const std::string& page, const std::string& series) {
  std::istringstream in(page);
  for (std::string line; std::getline(in, line);) {
    if (line.size() > series.size() && line.compare(0, series.size(), series) == 0 && line[series.size()] == ' ')
      return std::stod(line.substr(series.size() + 1));
  }
  return -1.0;
}

}  // namespace strata::test
