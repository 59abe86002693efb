// rayq::oracle — private: the public overloads for one number type, expanded once per TU
// (oracle_float.cpp, oracle_double.cpp) so that the two instantiations compile in parallel.
#pragma once

#include "convert.hpp"
#include "numeric.hpp"
#include "truth.hpp"

#define RAYQ_ORACLE_ENTRY_POINT(T, PRIM, IS_FLOAT)                                                  \
    Truth::Truth(const Ray<T>& ray, const PRIM& prim)                                             \
        : impl_(make_truth(exact::to_problem(ray, prim), IS_FLOAT)) {}                            \
    ExactHit exact_first_hit(const Ray<T>& ray, const PRIM& prim) { return Truth(ray, prim).first_hit(); } \
    Measurement measure(const Ray<T>& ray, const PRIM& prim, const std::optional<Hit<T>>& kernel) \
    {                                                                                             \
        return Truth(ray, prim).measure(kernel);                                                  \
    }

#define RAYQ_ORACLE_ENTRY_POINTS(T, IS_FLOAT)                                      \
    RAYQ_ORACLE_ENTRY_POINT(T, Sphere<T>, IS_FLOAT)                                \
    RAYQ_ORACLE_ENTRY_POINT(T, Plane<T>, IS_FLOAT)                                 \
    RAYQ_ORACLE_ENTRY_POINT(T, Disk<T>, IS_FLOAT)                                  \
    RAYQ_ORACLE_ENTRY_POINT(T, Parallelogram<T>, IS_FLOAT)                         \
    RAYQ_ORACLE_ENTRY_POINT(T, Triangle<T>, IS_FLOAT)                              \
    RAYQ_ORACLE_ENTRY_POINT(T, Cylinder<T>, IS_FLOAT)                              \
    RAYQ_ORACLE_ENTRY_POINT(T, Cone<T>, IS_FLOAT)                                  \
    RAYQ_ORACLE_ENTRY_POINT(T, Quadric<T>, IS_FLOAT)                               \
    RAYQ_ORACLE_ENTRY_POINT(T, Transformed<Sphere<T>>, IS_FLOAT)                   \
    RAYQ_ORACLE_ENTRY_POINT(T, Transformed<Plane<T>>, IS_FLOAT)                    \
    RAYQ_ORACLE_ENTRY_POINT(T, Transformed<Disk<T>>, IS_FLOAT)                     \
    RAYQ_ORACLE_ENTRY_POINT(T, Transformed<Parallelogram<T>>, IS_FLOAT)            \
    RAYQ_ORACLE_ENTRY_POINT(T, Transformed<Triangle<T>>, IS_FLOAT)                 \
    RAYQ_ORACLE_ENTRY_POINT(T, Transformed<Cylinder<T>>, IS_FLOAT)                 \
    RAYQ_ORACLE_ENTRY_POINT(T, Transformed<Cone<T>>, IS_FLOAT)                     \
    RAYQ_ORACLE_ENTRY_POINT(T, Transformed<Quadric<T>>, IS_FLOAT)                  \
    Affine3<T> rounded_inverse(const Affine3<T>& to_world)                         \
    {                                                                              \
        Affine3<T> out{};                                                          \
        const auto inv = exact::inverse(exact::to_affine(to_world));               \
        for (int i = 0; i < 3; ++i)                                                \
            for (int j = 0; j < 4; ++j)                                            \
                out.m[i][j] = inv ? exact::round_nearest<T>(inv->m[i][j])          \
                                  : std::numeric_limits<T>::quiet_NaN();           \
        return out;                                                                \
    }
