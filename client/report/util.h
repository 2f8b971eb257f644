#pragma once
// Internal to strata_report: number formatting, escaping, base64 and file output shared by the
// CSV, JSON and HTML writers.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "report/report.h"

namespace strata::report::detail {

// Shortest decimal form that reads back to the same double; "nan", "inf", "-inf" otherwise.
std::string format_number(double value);
// Fixed number of significant digits for people (tables): 3 -> "0.0123", "1.23e+04".
std::string format_short(double value, int digits = 3);

// Text for an HTML element or a double-quoted attribute.
std::string html_escape(std::string_view text);
// Standard base64 with padding (RFC 4648), for data: URIs.
std::string base64(std::span<const uint8_t> bytes);

// The scene names in the order they first appear in the runs, then in equal_time and insets.
std::vector<std::string> scene_order(const Report& report);

// Writes `text` to `path` (creating its parent directory); throws ReportError naming the file.
void write_text_file(const std::filesystem::path& path, std::string_view text, std::string_view what);

}  // namespace strata::report::detail
