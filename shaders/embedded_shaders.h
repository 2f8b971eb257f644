#pragma once
// SPIR-V compiled from shaders/passes/*.comp at build time (cmake/Shaders.cmake).
#include <cstdint>
#include <span>
#include <string_view>

namespace strata::shaders {
// Throws std::runtime_error when no shader of that name was compiled in.
std::span<const uint32_t> spirv(std::string_view name);
}  // namespace strata::shaders
