// rayq — forced inlining for the small arithmetic types (Vec3, Bounded, DoubleWord, error-free
// transformations). GCC's heuristics leave their operators as calls inside the accurate policy's
// template-heavy decisions, where a call costs more than the operation; forcing them inline
// measured: accurate sphere 14.6x -> 9.6x the cost of fast (rayq-bench, same run, default flags).
// RAYQ_NO_FLATTEN, defined before the first rayq include, drops RAYQ_FLATTEN: the same results,
// a slower `accurate`, and a much faster GCC build of code that instantiates many intersectors
// (certified_bound_test.cpp at -O1: 84 s -> 31 s); meant for test and debug builds.
#pragma once

#if defined(__GNUC__) || defined(__clang__)
#define RAYQ_INLINE inline __attribute__((always_inline))
#if defined(RAYQ_NO_FLATTEN)
#define RAYQ_FLATTEN
#else
#define RAYQ_FLATTEN __attribute__((flatten))
#endif
#define RAYQ_INLINE_LAMBDA __attribute__((always_inline))
#define RAYQ_NOINLINE __attribute__((noinline))
#define RAYQ_UNLIKELY(condition) __builtin_expect(!!(condition), 0)
#elif defined(_MSC_VER)
#define RAYQ_INLINE __forceinline
#define RAYQ_FLATTEN
#define RAYQ_INLINE_LAMBDA
#define RAYQ_NOINLINE __declspec(noinline)
#define RAYQ_UNLIKELY(condition) (condition)
#else
#define RAYQ_INLINE inline
#define RAYQ_FLATTEN
#define RAYQ_INLINE_LAMBDA
#define RAYQ_NOINLINE
#define RAYQ_UNLIKELY(condition) (condition)
#endif
