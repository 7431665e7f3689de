#pragma once
// The tessellators (tessellate_sphere / _capsule / _cylinder / _box, flat_grid, lathe) live in
// solid_test_meshes.hpp with the other midphase test meshes; this header keeps the name for
// the files that include it.
#include "support/solid_test_meshes.hpp"
