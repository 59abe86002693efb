// rayq::embree — the Embree 3 adapter (adapters/embree, CMake target rayq::embree): rayq
// primitives as Embree user geometry. See rayq/embree/user_geometry.hpp.
#pragma once

#include <rayq/embree/bounds.hpp>
#include <rayq/embree/user_geometry.hpp>
