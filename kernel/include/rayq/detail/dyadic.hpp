// rayq — exact dyadic numbers m·2^e with an integer m of any size and an unbounded exponent (the
// representation of CGAL's MP_Float and Gmpzf). Every float and double is one, and +, − and × are
// exact with no range limit. The accurate policy's last resort (adaptive_sign, exact.hpp): it runs
// only when an expansion's product under- or overflowed, where expansions are no longer exact
// (inputs whose magnitudes span beyond about 2^±(max_exponent / degree): a subnormal beside 1,
// 2^900 beside 2^-300).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

namespace rayq::detail {

// One limb product: hi·2^64 + lo = a·b + addend + carry, which cannot overflow 128 bits. With
// GCC's and clang's 128-bit integer where there is one; the portable form (four 32-bit products)
// elsewhere, and in a test that checks the two agree.
struct WideProduct {
    std::uint64_t lo, hi;
};
inline WideProduct multiply_add_portable(std::uint64_t a, std::uint64_t b, std::uint64_t addend, std::uint64_t carry)
{
    const std::uint64_t mask = 0xffffffffu;
    const std::uint64_t a0 = a & mask, a1 = a >> 32, b0 = b & mask, b1 = b >> 32;
    const std::uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    // The middle column: each term < 2^64 − 2^33 + 3, their sum's carries counted apart.
    const std::uint64_t middle = (p00 >> 32) + (p01 & mask) + (p10 & mask);
    std::uint64_t lo = (middle << 32) | (p00 & mask);
    std::uint64_t hi = p11 + (p01 >> 32) + (p10 >> 32) + (middle >> 32);
    lo += addend;
    hi += lo < addend;
    lo += carry;
    hi += lo < carry;
    return {lo, hi};
}
inline WideProduct multiply_add(std::uint64_t a, std::uint64_t b, std::uint64_t addend, std::uint64_t carry)
{
#if defined(__SIZEOF_INT128__)
    __extension__ typedef unsigned __int128 Wide;  // NOLINT: GCC and clang's 128-bit integer
    const Wide t = Wide(a) * b + addend + carry;
    return {static_cast<std::uint64_t>(t), static_cast<std::uint64_t>(t >> 64)};
#else
    return multiply_add_portable(a, b, addend, carry);
#endif
}

class Dyadic {
public:
    Dyadic() = default;
    template <class T, std::enable_if_t<std::is_floating_point_v<T>, int> = 0>
    Dyadic(T x)  // NOLINT(google-explicit-constructor): numbers convert implicitly, as for Expansion
    {
        const double d = static_cast<double>(x);  // exact for float and double
        if (!std::isfinite(d)) {
            finite_ = false;
            return;
        }
        if (d == 0.0) return;
        int e = 0;
        const double m = std::frexp(std::abs(d), &e);  // |d| = m·2^e, m in [1/2, 1)
        limbs_ = {static_cast<std::uint64_t>(std::ldexp(m, 53))};
        exponent_ = e - 53;
        sign_ = d > 0 ? 1 : -1;
        normalize();
    }

    int sign() const { return sign_; }
    // False when an input was infinite or NaN (then the value means nothing).
    bool finite() const { return finite_; }
    // The value truncated to 53 bits, with its exponent apart (tests and diagnostics):
    // value = mantissa·2^exponent up to the truncation, mantissa in [1/2, 1) unless zero.
    std::pair<double, long> frexp() const
    {
        if (sign_ == 0) return {0.0, 0};
        const long length = 64L * long(limbs_.size() - 1) + (64 - count_leading_zeros(limbs_.back()));
        // Bits [length − 53, length): from the top limb and, when it has fewer, the one below.
        const int kept = int(std::min(length, 53L));
        const long low = length - kept;
        const std::size_t at = std::size_t(low / 64);
        const int shift = int(low % 64);
        std::uint64_t top = limbs_[at] >> shift;
        if (shift != 0 && at + 1 < limbs_.size()) top |= limbs_[at + 1] << (64 - shift);
        top &= (std::uint64_t(1) << kept) - 1;
        return {sign_ * std::ldexp(double(top), -kept), length + exponent_};
    }

    friend Dyadic operator-(Dyadic a)
    {
        a.sign_ = -a.sign_;
        return a;
    }
    friend Dyadic operator+(const Dyadic& a, const Dyadic& b)
    {
        if (!a.finite_ || !b.finite_) return not_finite();
        if (a.sign_ == 0) return b;
        if (b.sign_ == 0) return a;
        // The coarser operand moved onto the finer one's grid (its only copy), then the other
        // added to or subtracted from it in place, as integers.
        const Dyadic& coarse = a.exponent_ >= b.exponent_ ? a : b;
        const Dyadic& fine = a.exponent_ >= b.exponent_ ? b : a;
        Dyadic r;
        r.limbs_ = shifted_left(coarse.limbs_, coarse.exponent_ - fine.exponent_, fine.limbs_.size() + 1);
        r.exponent_ = fine.exponent_;
        if (coarse.sign_ == fine.sign_) {
            add_in_place(r.limbs_, fine.limbs_);
            r.sign_ = coarse.sign_;
        } else {
            const int c = compared(r.limbs_, fine.limbs_);
            if (c == 0) return Dyadic{};
            subtract_in_place(r.limbs_, fine.limbs_, c > 0);
            r.sign_ = c > 0 ? coarse.sign_ : fine.sign_;
        }
        r.normalize();
        return r;
    }
    friend Dyadic operator-(const Dyadic& a, const Dyadic& b) { return a + (-b); }
    friend Dyadic operator*(const Dyadic& a, const Dyadic& b)
    {
        if (!a.finite_ || !b.finite_) return not_finite();
        if (a.sign_ == 0 || b.sign_ == 0) return Dyadic{};
        Dyadic r;
        r.limbs_.assign(a.limbs_.size() + b.limbs_.size(), 0);
        for (std::size_t i = 0; i < a.limbs_.size(); ++i) {
            std::uint64_t carry = 0;
            for (std::size_t j = 0; j < b.limbs_.size(); ++j) {
                const WideProduct t = multiply_add(a.limbs_[i], b.limbs_[j], r.limbs_[i + j], carry);
                r.limbs_[i + j] = t.lo;
                carry = t.hi;
            }
            r.limbs_[i + b.limbs_.size()] = carry;
        }
        r.exponent_ = a.exponent_ + b.exponent_;
        r.sign_ = a.sign_ * b.sign_;
        r.normalize();  // odd times odd is odd: only a top limb to drop
        return r;
    }
    friend Dyadic& operator+=(Dyadic& a, const Dyadic& b) { return a = a + b; }

private:
    using Limbs = std::vector<std::uint64_t>;  // little-endian

    static int count_leading_zeros(std::uint64_t x)  // x != 0
    {
#if defined(__GNUC__)
        return __builtin_clzll(x);
#else
        int n = 0;
        while ((x & (std::uint64_t(1) << 63)) == 0) x <<= 1, ++n;
        return n;
#endif
    }
    static int count_trailing_zeros(std::uint64_t x)  // x != 0
    {
#if defined(__GNUC__)
        return __builtin_ctzll(x);
#else
        int n = 0;
        while ((x & 1u) == 0) x >>= 1, ++n;
        return n;
#endif
    }
    static Dyadic not_finite()
    {
        Dyadic r;
        r.finite_ = false;
        return r;
    }
    // x·2^bits, with room for at least `size` limbs.
    static Limbs shifted_left(const Limbs& x, long bits, std::size_t size)
    {
        const std::size_t whole = static_cast<std::size_t>(bits / 64);
        const int part = static_cast<int>(bits % 64);
        Limbs r;
        r.reserve(std::max(whole + x.size() + 1, size));
        r.assign(whole, 0);
        std::uint64_t carry = 0;
        for (std::uint64_t limb : x) {
            r.push_back(part == 0 ? limb : (limb << part) | carry);
            carry = part == 0 ? 0 : limb >> (64 - part);
        }
        if (carry != 0) r.push_back(carry);
        return r;
    }
    // Magnitudes without leading zero limbs compare by length first.
    static int compared(const Limbs& x, const Limbs& y)
    {
        std::size_t nx = x.size(), ny = y.size();
        while (nx > 0 && x[nx - 1] == 0) --nx;
        while (ny > 0 && y[ny - 1] == 0) --ny;
        if (nx != ny) return nx > ny ? 1 : -1;
        for (std::size_t i = nx; i-- > 0;)
            if (x[i] != y[i]) return x[i] > y[i] ? 1 : -1;
        return 0;
    }
    static void add_in_place(Limbs& x, const Limbs& y)  // x += y
    {
        if (x.size() < y.size()) x.resize(y.size(), 0);
        x.push_back(0);
        std::uint64_t carry = 0;
        for (std::size_t i = 0; i < x.size(); ++i) {
            const std::uint64_t yi = i < y.size() ? y[i] : 0u;
            const std::uint64_t s = x[i] + yi;
            const std::uint64_t t = s + carry;
            carry = std::uint64_t(s < yi) + std::uint64_t(t < s);  // at most one of them
            x[i] = t;
            if (carry == 0 && i >= y.size()) break;
        }
    }
    // x −= y when x_larger, else x = y − x (the larger minus the smaller, either way).
    static void subtract_in_place(Limbs& x, const Limbs& y, bool x_larger)
    {
        if (x.size() < y.size()) x.resize(y.size(), 0);
        std::uint64_t borrow = 0;
        for (std::size_t i = 0; i < x.size(); ++i) {
            const std::uint64_t yi = i < y.size() ? y[i] : 0u;
            const std::uint64_t minuend = x_larger ? x[i] : yi, subtrahend = x_larger ? yi : x[i];
            const std::uint64_t d = minuend - subtrahend;
            const std::uint64_t t = d - borrow;
            borrow = std::uint64_t(minuend < subtrahend) + std::uint64_t(d < borrow);  // at most one of them
            x[i] = t;
        }
    }
    // An odd integer (trailing zero bits moved into the exponent) with a nonzero top limb: keeps
    // sums of far-apart terms as short as their span.
    void normalize()
    {
        while (!limbs_.empty() && limbs_.back() == 0) limbs_.pop_back();
        if (limbs_.empty()) {
            sign_ = 0;
            exponent_ = 0;
            return;
        }
        std::size_t zeros = 0;
        while (limbs_[zeros] == 0) ++zeros;
        const int bits = count_trailing_zeros(limbs_[zeros]);
        if (zeros == 0 && bits == 0) return;
        for (std::size_t i = zeros; i < limbs_.size(); ++i) {
            const std::uint64_t high = i + 1 < limbs_.size() ? limbs_[i + 1] : 0u;
            limbs_[i - zeros] = bits == 0 ? limbs_[i] : (limbs_[i] >> bits) | (high << (64 - bits));
        }
        limbs_.resize(limbs_.size() - zeros);
        while (!limbs_.empty() && limbs_.back() == 0) limbs_.pop_back();
        exponent_ += 64L * long(zeros) + bits;
    }

    Limbs limbs_;        // |value| = limbs·2^exponent, odd; empty for zero
    long exponent_ = 0;
    int sign_ = 0;
    bool finite_ = true;
};

}  // namespace rayq::detail
