// rayq — SIMD lanes for the batch paths: std::experimental::native_simd where the standard
// library has it (libstdc++ ≥ 11; header-only, no flags imposed on users), one lane of plain T
// elsewhere. Batch code is written once over `Lanes<T>::pack` and runs unchanged on either.
//
// Why not a plain structure-of-arrays loop: GCC does not vectorize loops calling std::sqrt (it
// may set errno) unless users pass -fno-math-errno, which a header-only library cannot impose.
// Define RAYQ_NO_STD_SIMD to force the one-lane fallback (e.g. for clang 14 with libstdc++ 12
// under AVX-512, whose <experimental/simd> miscompiled in our measurements: issue 7).
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>
#if defined(__has_include)
#if __has_include(<bit>) && __cplusplus >= 202002L
#include <bit>
#endif
#endif

#if !defined(RAYQ_NO_STD_SIMD) && defined(__has_include)
#if __has_include(<experimental/simd>)
#include <experimental/simd>
#if defined(__cpp_lib_experimental_parallel_simd)
#define RAYQ_HAS_STD_SIMD 1
#endif
#endif
#endif

namespace rayq::detail {

#if defined(RAYQ_HAS_STD_SIMD)

template <class M, class = void>
struct has_to_bitset : std::false_type {};
template <class M>
struct has_to_bitset<M, std::void_t<decltype(std::declval<const M&>().__to_bitset().to_ullong())>> : std::true_type {};

template <class T>
struct Lanes {
    using pack = std::experimental::native_simd<T>;
    using mask = typename pack::mask_type;
    static constexpr int width = static_cast<int>(pack::size());

    static pack load(const T* p) { return pack(p, std::experimental::element_aligned); }
    static std::uint32_t bits(const mask& m)  // lane i -> bit i
    {
        // libstdc++'s bitset extension is one movmsk/kmov; the lane loop is what the TS offers
        // and GCC 12 compiles it lane by lane (4–5× the filter's time on AVX2, measured).
        if constexpr (has_to_bitset<mask>::value) {
            return static_cast<std::uint32_t>(m.__to_bitset().to_ullong());
        } else {
            std::uint32_t b = 0;
            for (int i = 0; i < width; ++i) b |= static_cast<std::uint32_t>(static_cast<bool>(m[i])) << i;
            return b;
        }
    }
};

#else

template <class T>
struct Lanes {
    using pack = T;
    using mask = bool;
    static constexpr int width = 1;

    static pack load(const T* p) { return *p; }
    static std::uint32_t bits(mask m) { return m ? 1u : 0u; }
};

#endif

// Whether every lane of a mask is set, and lane-wise |v|: for Lanes' packs and for one plain T
// (bool masks), so that a test written over packs also runs on one scalar (batch/filter_core.hpp).
template <class M>
inline bool all_lanes(const M& m)
{
    if constexpr (std::is_same_v<M, bool>) return m;
#if defined(RAYQ_HAS_STD_SIMD)
    else return std::experimental::all_of(m);
#endif
}
template <class P>
inline P abs_lanes(const P& v)
{
    if constexpr (std::is_arithmetic_v<P>) return v < P(0) ? -v : v;
#if defined(RAYQ_HAS_STD_SIMD)
    else return std::experimental::abs(v);
#endif
}

// Lane columns (structure of arrays) start on a 64-byte boundary, so that a lane group's load never
// spans two cache lines: std::vector's default allocation is only 16-byte aligned, and at 16 float
// lanes every group of such a column was a split load.
template <class T>
struct LaneAllocator {
    using value_type = T;
    static constexpr std::size_t alignment = 64;
    LaneAllocator() = default;
    template <class U>
    LaneAllocator(const LaneAllocator<U>&) noexcept {}
    T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t{alignment})); }
    void deallocate(T* p, std::size_t) noexcept { ::operator delete(p, std::align_val_t{alignment}); }
    template <class U>
    bool operator==(const LaneAllocator<U>&) const noexcept { return true; }
    template <class U>
    bool operator!=(const LaneAllocator<U>&) const noexcept { return false; }
};
template <class T>
using LaneColumn = std::vector<T, LaneAllocator<T>>;

// The lowest set bit's index by a de Bruijn multiply (Leiserson, Prokop, Randall, "Using de Bruijn
// Sequences to Index a 1 in a Computer Word", 1998): branch-free in standard C++.
constexpr int lowest_bit_de_bruijn(std::uint32_t m)
{
    constexpr int position[32] = {0,  1,  28, 2,  29, 14, 24, 3, 30, 22, 20, 15, 25, 17, 4,  8,
                                  31, 27, 13, 23, 21, 19, 16, 7, 26, 12, 18, 6,  11, 5,  10, 9};
    return position[((m & (0u - m)) * 0x077CB531u) >> 27];
}

// Index of the lowest set bit of a nonzero lane mask: one tzcnt/bsf where the compiler has it. Not
// a shifting loop: GCC did not recognize one, and a scene's candidate lane paid an iteration per
// lane below it and a mispredicted exit (rayq-bench-embree, -march=native, float spheres under
// `fast` with point and normal: see the commit that replaced it).
inline int lowest_bit(std::uint32_t m)
{
#if defined(__cpp_lib_bitops)
    return std::countr_zero(m);
#elif defined(__GNUC__) || defined(__clang__)
    return __builtin_ctz(m);
#else
    return lowest_bit_de_bruijn(m);
#endif
}

}  // namespace rayq::detail
