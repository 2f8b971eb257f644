#pragma once
// night-street's layout, shared by its two halves: night_street.cpp builds the street, its
// buildings and their lit windows; night_street_lights.cpp its 64 punctual lights with their
// fixtures, the lanterns that sway and the cars that drive.
#include <cstdint>

#include "scene/builtin/common.h"

namespace strata::scene::builtin::night_street {

inline constexpr float kRoadHalfWidth = 4.0f;  // the road: x in [-4, 4]
inline constexpr float kFacadeX = 7.0f;        // facades at x = -7 and 7, sidewalks between
inline constexpr float kCurb = 0.15f;          // sidewalk height
inline constexpr float kNearZ = 10.0f;         // the street runs from z = 10 ...
inline constexpr float kBlockLength = 11.0f;   // ... past six buildings of 11 m a side ...
inline constexpr uint32_t kBlocks = 6;
inline constexpr float kCrossZ = kNearZ - kBlockLength * kBlocks;  // ... to a cross street at z = -56 ...
inline constexpr float kFarFacadeZ = -64.0f;                       // ... closed by a facade at z = -64

// Materials of the fixtures and the cars the lights come with.
struct FixtureMaterials {
  uint32_t metal;      // lamp posts, brackets
  uint32_t frame;      // lantern frames: black and rough, so that the bulb 10 cm away leaves no bright spot on them
  uint32_t tyre;       // wheels
  uint32_t glass;      // car windows
  uint32_t paint[2];   // one per car
};

// Street lamps, shop-front lights, swaying lanterns, two cars with their headlights and tail
// lights, floodlights and high masts at the far end: 64 lights in all, with their geometry and
// tracks.
void add_lights(SceneBuilder& b, const FixtureMaterials& m);

}  // namespace strata::scene::builtin::night_street
