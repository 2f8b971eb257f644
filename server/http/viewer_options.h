#pragma once
// The render options the viewer's panel offers. Which rows of the option table (options/option_table.h)
// the panel shows, and its labels, are the viewer's; everything else (kind, range, the methods an
// option applies to) comes from the table, so the panel cannot disagree with the service, which
// checks the values as it checks any FrameInput's.
#include <nlohmann/json.hpp>

namespace strata::http {

// [{field, label, kind ("uint", "float" or "bool"), min, max, step, restir_only}] as the page reads it
// (sent in the hello reply). Throws std::logic_error naming a field that the option table lacks.
nlohmann::json viewer_options_json();

}  // namespace strata::http
