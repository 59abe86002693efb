// rayq — forced inlining for the small arithmetic types (Vec3, Bounded, DoubleWord, error-free
// transformations). GCC's heuristics leave their operators as calls inside the accurate policy's
// template-heavy decisions, where a call costs more than the operation; forcing them inline
// measured: accurate sphere 14.6x -> 9.6x the cost of fast (rayq-bench, same run, default flags).
// RAYQ_NO_FLATTEN, defined before the first rayq include, drops RAYQ_FLATTEN: the same results,
// a slower `accurate`, and a much faster GCC build of code that instantiates many intersectors
// (certified_bound_test.cpp at -O1: 84 s -> 31 s); meant for test and debug builds.
// RAYQ_NO_FORCED_INLINE drops RAYQ_FLATTEN and the forced inlining too, leaving inlining to the
// compiler: the same results, slower code, and a much faster build where the compiler's back end
// is the cost, as under sanitizers (clang 14, ASan + UBSan, -O1: the benchmark rayq-bench-scene
// 114 s -> 33 s, the kernel test suite 437 s -> 229 s); tools/sanitize builds everything so.
#pragma once

#if defined(__GNUC__) || defined(__clang__)
#if defined(RAYQ_NO_FORCED_INLINE)
#define RAYQ_INLINE inline
#define RAYQ_INLINE_LAMBDA
#else
#define RAYQ_INLINE inline __attribute__((always_inline))
#define RAYQ_INLINE_LAMBDA __attribute__((always_inline))
#endif
#if defined(RAYQ_NO_FLATTEN) || defined(RAYQ_NO_FORCED_INLINE)
#define RAYQ_FLATTEN
#else
#define RAYQ_FLATTEN __attribute__((flatten))
#endif
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
