#pragma once
// What the ops tests share: a stratad with its metrics and HTTP addresses read from its log, Debian
// tools by path (overridable), and small file helpers.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "http_get.h"
#include "process.h"

namespace strata::test {

std::string read_text(const std::filesystem::path& path);
void write_text(const std::filesystem::path& path, const std::string& text);
// $name when set, else `fallback` (a Debian path).
std::string tool_path(const char* env, const std::string& fallback);

// `stratad serve` plus `args`, ready; metrics_address()/http_address() are what it printed
// ("metrics on http://..." and "dashboard on http://...") when those endpoints were asked for.
class OpsDaemon {
 public:
  explicit OpsDaemon(const std::vector<std::string>& args);
  const std::string& address() const { return daemon_.address(); }
  const std::string& metrics_address() const { return metrics_; }
  const std::string& http_address() const { return http_; }
  Process& process() { return daemon_.process(); }

 private:
  Daemon daemon_;
  std::string metrics_, http_;
};

// Value of the sample `series` (the exact text before the value, e.g. `x_total{a="b"}`) on a
// Prometheus text page; -1 when absent.
double sample_value(const std::string& page, const std::string& series);

}  // namespace strata::test
