// rayq::fuzz — check() (invariants.hpp) compiled once per primitive family, in the library
// rayq::fuzz_checks (validation/fuzz/src/checks_<family>.cpp), instead of in every program that
// fuzzes: its instantiations (every primitive, both number types, three policies, the scene and
// stream paths, the binary128 reference) take one to two minutes per program to compile, and four
// programs use them (rayq-fuzz, rayq-validate's fuzz campaign, the edge-case test, the libFuzzer
// harnesses). Include this instead of invariants.hpp and link rayq::fuzz_checks.
#pragma once

#include "invariants.hpp"

// The primitives the decoder (decoder.hpp) makes, per harness family, for number type T.
#define RAYQ_FUZZ_FLAT_PRIMITIVES(X, T) X(Plane<T>) X(Disk<T>) X(Parallelogram<T>) X(Triangle<T>)
#define RAYQ_FUZZ_SPHERE_PRIMITIVES(X, T) X(Sphere<T>)
#define RAYQ_FUZZ_AXIAL_PRIMITIVES(X, T) X(Cylinder<T>) X(Cone<T>)
#define RAYQ_FUZZ_QUADRIC_PRIMITIVES(X, T) X(Quadric<T>)
#define RAYQ_FUZZ_TRANSFORMED_PRIMITIVES(X, T)                                                                  \
    X(Transformed<Sphere<T>>) X(Transformed<Plane<T>>) X(Transformed<Disk<T>>) X(Transformed<Parallelogram<T>>) \
    X(Transformed<Triangle<T>>) X(Transformed<Cylinder<T>>) X(Transformed<Cone<T>>) X(Transformed<Quadric<T>>)
#define RAYQ_FUZZ_ALL_PRIMITIVES(X, T)                                                                          \
    RAYQ_FUZZ_FLAT_PRIMITIVES(X, T) RAYQ_FUZZ_SPHERE_PRIMITIVES(X, T) RAYQ_FUZZ_AXIAL_PRIMITIVES(X, T)        \
    RAYQ_FUZZ_QUADRIC_PRIMITIVES(X, T) RAYQ_FUZZ_TRANSFORMED_PRIMITIVES(X, T)

#define RAYQ_FUZZ_CHECK_EXTERN(Prim) extern template Checked check<Prim>(const Ray<scalar_t<Prim>>&, const Prim&, const Options&);
#define RAYQ_FUZZ_CHECK_INSTANTIATE(Prim) template Checked check<Prim>(const Ray<scalar_t<Prim>>&, const Prim&, const Options&);

namespace rayq::fuzz {
RAYQ_FUZZ_ALL_PRIMITIVES(RAYQ_FUZZ_CHECK_EXTERN, float)
RAYQ_FUZZ_ALL_PRIMITIVES(RAYQ_FUZZ_CHECK_EXTERN, double)
}  // namespace rayq::fuzz
