#pragma once
// docs/OPTIONS.md, generated from the option table (`stratad options --markdown`); a test holds the
// checked-in file equal to it.
#include <string>

namespace strata::options {

std::string options_markdown();

}  // namespace strata::options
