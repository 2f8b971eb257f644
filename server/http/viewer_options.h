#pragma once
// The render options the viewer's panel offers: each a field of strata.v1.RenderOptions by its
// proto name, with the control's range. This is the one place the viewer names options; the page
// builds its panel from this list (sent in the hello reply) and sets the fields by these names, and
// the service checks the values as it checks any FrameInput's.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace strata::http {

struct ViewerOption {
  const char* field;   // RenderOptions field (proto name)
  const char* label;
  double min, max, step;  // for numbers; a bool field ignores them
  bool restir_only;    // only the restir-* methods use it
};

const std::vector<ViewerOption>& viewer_options();

// The list as the page reads it: [{field, label, kind ("uint", "float" or "bool"), min, max, step,
// restir_only}], kinds taken from the proto's descriptor. Throws std::logic_error naming a field that
// RenderOptions does not have.
nlohmann::json viewer_options_json();

}  // namespace strata::http
