// Lets one header compile as GLSL 460 and as C++20, so that structs and math that both the host
// and the device use are written once (docs/ARCHITECTURE.md, Layout).
#ifndef STRATA_LANG_H
#define STRATA_LANG_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/packing.hpp>
#define STRATA_NAMESPACE_BEGIN namespace strata::gpu { using namespace glm; using uint = std::uint32_t;
#define STRATA_NAMESPACE_END }
#define INOUT(T) T&
#define OUT(T) T&
#define CONST_DEF inline constexpr
#define INLINE inline
#else
#define STRATA_NAMESPACE_BEGIN
#define STRATA_NAMESPACE_END
#define INOUT(T) inout T
#define OUT(T) out T
#define CONST_DEF const
#define INLINE
#endif

#endif
