// rayq — ray–quadric intersection. The umbrella header: every primitive and query.
#pragma once

#include "cone.hpp"
#include "cylinder.hpp"
#include "disk.hpp"
#include "hit.hpp"
#include "parallelogram.hpp"
#include "plane.hpp"
#include "policy.hpp"
#include "quadratic.hpp"
#include "quadric.hpp"
#include "query.hpp"
#include "ray.hpp"
#include "sphere.hpp"
#include "transformed.hpp"
#include "triangle.hpp"
#include "validation.hpp"
#include "vec3.hpp"
