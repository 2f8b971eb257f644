#pragma once
// Internal to strata_report: the perceptual colour map of the error maps (matplotlib's magma).
#include <array>
#include <cstdint>

namespace strata::report::detail {

// t in [0, 1] (clamped; NaN gives 1) to 8-bit sRGB.
std::array<uint8_t, 3> magma(float t);

}  // namespace strata::report::detail
