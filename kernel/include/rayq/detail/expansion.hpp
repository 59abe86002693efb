// rayq — exact arithmetic on floating-point expansions (Shewchuk, "Adaptive Precision
// Floating-Point Arithmetic and Fast Robust Geometric Predicates", 1997): a value is an unevaluated
// sum of non-overlapping floats, so +, − and × are exact. Used only where a filtered decision could
// not be made (see adaptive.hpp). Exact while no product under- or overflows, i.e. for inputs
// whose magnitudes stay within about 2^±(max_exponent / degree) of each other.
#pragma once

#include <cmath>
#include <vector>

#include "eft.hpp"

namespace rayq::detail {

template <class T>
class Expansion {
public:
    Expansion() = default;
    Expansion(T x)  // NOLINT(google-explicit-constructor): numbers convert implicitly, as for Bounded
    {
        if (x != T(0)) c_.push_back(x);
    }

    int sign() const { return c_.empty() ? 0 : (c_.back() > T(0) ? 1 : -1); }
    T estimate() const
    {
        T s = T(0);
        for (T x : c_) s += x;
        return s;
    }
    std::size_t size() const { return c_.size(); }

    friend Expansion operator+(const Expansion& a, const Expansion& b)
    {
        Expansion r = a.size() >= b.size() ? a : b;
        for (T x : (a.size() >= b.size() ? b : a).c_) r.grow(x);
        r.compress();
        return r;
    }
    friend Expansion operator-(const Expansion& a) { Expansion r = a; for (T& x : r.c_) x = -x; return r; }
    friend Expansion operator-(const Expansion& a, const Expansion& b) { return a + (-b); }
    friend Expansion operator*(const Expansion& a, const Expansion& b)
    {
        Expansion r;
        const Expansion& big = a.size() >= b.size() ? a : b;
        for (T x : (a.size() >= b.size() ? b : a).c_) {
            for (T e : big.c_) {
                const Pair<T> p = two_product(e, x);
                r.grow(p.lo);
                r.grow(p.hi);
            }
            r.compress();
        }
        return r;
    }
    friend Expansion& operator+=(Expansion& a, const Expansion& b) { return a = a + b; }

private:
    // GROW-EXPANSION with zero elimination: adds b, keeping components non-overlapping and
    // increasing in magnitude.
    void grow(T b)
    {
        std::vector<T> h;
        h.reserve(c_.size() + 1);
        T q = b;
        for (T e : c_) {
            const Pair<T> s = two_sum(q, e);
            q = s.hi;
            if (s.lo != T(0)) h.push_back(s.lo);
        }
        if (q != T(0)) h.push_back(q);
        c_.swap(h);
    }
    // COMPRESS: the same value in as few components as possible; the largest keeps the sign.
    void compress()
    {
        const int n = static_cast<int>(c_.size());
        if (n < 2) return;
        std::vector<T> h(c_.size());
        int bottom = n - 1;
        T q = c_[n - 1];
        for (int i = n - 2; i >= 0; --i) {
            const T sum = q + c_[i];
            const T err = c_[i] - (sum - q);  // fast two-sum: |q| >= |c_i| holds here
            if (err != T(0)) {
                h[bottom--] = sum;
                q = err;
            } else {
                q = sum;
            }
        }
        int top = 0;
        for (int i = bottom + 1; i < n; ++i) {
            const T sum = h[i] + q;
            const T err = q - (sum - h[i]);
            if (err != T(0)) h[top++] = err;
            q = sum;
        }
        h[top++] = q;
        h.resize(top);
        if (h.size() == 1 && h[0] == T(0)) h.clear();
        c_.swap(h);
    }

    std::vector<T> c_;  // increasing magnitude, no zeros
};

}  // namespace rayq::detail
