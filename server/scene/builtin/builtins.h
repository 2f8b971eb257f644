#pragma once
// One generator per built-in scene, each in its own file; registry.cpp names them.
#include "scene/scene.h"

namespace strata::scene::builtin {

Scene make_cornell();
Scene make_cornell_lamps();  // cornell lit by punctual lights
Scene make_carousel();
Scene make_carousel_bounce();
Scene make_lod_cliff();
Scene make_chess();
Scene make_foliage();
Scene make_overlap_uv();
Scene make_stiff();
Scene make_lod_bounce();
Scene make_courtyard();  // textures, alpha-masked leaves, punctual lights and a sky map
Scene make_night_street();  // a street at night: 64 punctual lights, hundreds of lit windows
Scene make_atrium();  // a closed room lit by a sun and a sky through its openings
Scene make_characters();  // a skinned flag and a morphing blob in a lit room

}  // namespace strata::scene::builtin
