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
        const auto bits = static_cast<std::uint64_t>(std::ldexp(m, 53));
        limbs_ = {static_cast<std::uint32_t>(bits), static_cast<std::uint32_t>(bits >> 32)};
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
        const long length = 32L * long(limbs_.size() - 1) + (32 - count_leading_zeros(limbs_.back()));
        std::uint64_t top = 0;  // bits [length − 53, length)
        for (long bit = length - 1; bit >= std::max(0L, length - 53); --bit)
            top = (top << 1) | ((limbs_[std::size_t(bit / 32)] >> (bit % 32)) & 1u);
        const int kept = int(std::min(length, 53L));
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
                const std::uint64_t t = std::uint64_t(a.limbs_[i]) * b.limbs_[j] + r.limbs_[i + j] + carry;
                r.limbs_[i + j] = static_cast<std::uint32_t>(t);
                carry = t >> 32;
            }
            r.limbs_[i + b.limbs_.size()] = static_cast<std::uint32_t>(carry);
        }
        r.exponent_ = a.exponent_ + b.exponent_;
        r.sign_ = a.sign_ * b.sign_;
        r.normalize();  // odd times odd is odd: only a top limb to drop
        return r;
    }
    friend Dyadic& operator+=(Dyadic& a, const Dyadic& b) { return a = a + b; }

private:
    using Limbs = std::vector<std::uint32_t>;  // little-endian

    static int count_leading_zeros(std::uint32_t x)
    {
        int n = 0;
        while ((x & 0x80000000u) == 0) x <<= 1, ++n;
        return n;
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
        const std::size_t whole = static_cast<std::size_t>(bits / 32);
        const int part = static_cast<int>(bits % 32);
        Limbs r;
        r.reserve(std::max(whole + x.size() + 1, size));
        r.assign(whole, 0);
        std::uint32_t carry = 0;
        for (std::uint32_t limb : x) {
            r.push_back(part == 0 ? limb : (limb << part) | carry);
            carry = part == 0 ? 0 : limb >> (32 - part);
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
            const std::uint64_t t = std::uint64_t(x[i]) + (i < y.size() ? y[i] : 0u) + carry;
            x[i] = static_cast<std::uint32_t>(t);
            carry = t >> 32;
            if (carry == 0 && i >= y.size()) break;
        }
    }
    // x −= y when x_larger, else x = y − x (the larger minus the smaller, either way).
    static void subtract_in_place(Limbs& x, const Limbs& y, bool x_larger)
    {
        if (x.size() < y.size()) x.resize(y.size(), 0);
        std::int64_t borrow = 0;
        for (std::size_t i = 0; i < x.size(); ++i) {
            const std::int64_t xi = x[i], yi = i < y.size() ? std::int64_t(y[i]) : 0;
            std::int64_t t = (x_larger ? xi - yi : yi - xi) - borrow;
            borrow = t < 0 ? 1 : 0;
            if (t < 0) t += std::int64_t(1) << 32;
            x[i] = static_cast<std::uint32_t>(t);
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
        int bits = 0;
        while (((limbs_[zeros] >> bits) & 1u) == 0) ++bits;
        if (zeros == 0 && bits == 0) return;
        for (std::size_t i = zeros; i < limbs_.size(); ++i) {
            const std::uint32_t high = i + 1 < limbs_.size() ? limbs_[i + 1] : 0u;
            limbs_[i - zeros] = bits == 0 ? limbs_[i] : (limbs_[i] >> bits) | (high << (32 - bits));
        }
        limbs_.resize(limbs_.size() - zeros);
        while (!limbs_.empty() && limbs_.back() == 0) limbs_.pop_back();
        exponent_ += 32L * long(zeros) + bits;
    }

    Limbs limbs_;        // |value| = limbs·2^exponent, odd; empty for zero
    long exponent_ = 0;
    int sign_ = 0;
    bool finite_ = true;
};

}  // namespace rayq::detail
