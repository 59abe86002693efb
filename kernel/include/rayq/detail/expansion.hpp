// rayq — exact arithmetic on floating-point expansions (Shewchuk, "Adaptive Precision
// Floating-Point Arithmetic and Fast Robust Geometric Predicates", 1997): a value is an unevaluated
// sum of non-overlapping floats, so +, − and × are exact. Used only where a filtered decision could
// not be made (adaptive_sign, exact.hpp). Exact while no product under- or overflows, i.e. for
// inputs whose magnitudes stay within about 2^±(max_exponent / degree) of each other; an expansion
// says when one did (exact()), and the caller turns to Dyadic (dyadic.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "eft.hpp"

namespace rayq::detail {

// An expansion's components: inline up to 16 (products of a few inputs need no more), on the heap
// beyond. (With a std::vector alone, allocation was about 40% of the exact path's instructions on
// the sphere fuzz harness's replay, callgrind.)
template <class T>
class Components {
    static constexpr std::size_t inline_capacity = 16;

public:
    Components() = default;
    Components(const Components& o) : n_(o.n_), on_heap_(o.on_heap_), heap_(o.heap_) { copy_inline(o); }
    Components(Components&& o) noexcept : n_(o.n_), on_heap_(o.on_heap_), heap_(std::move(o.heap_)) { copy_inline(o); }
    Components& operator=(const Components& o)
    {
        if (this != &o) n_ = o.n_, on_heap_ = o.on_heap_, heap_ = o.heap_, copy_inline(o);
        return *this;
    }
    Components& operator=(Components&& o) noexcept
    {
        if (this != &o) n_ = o.n_, on_heap_ = o.on_heap_, heap_ = std::move(o.heap_), copy_inline(o);
        return *this;
    }

    std::size_t size() const { return on_heap_ ? heap_.size() : n_; }
    bool empty() const { return size() == 0; }
    T* data() { return on_heap_ ? heap_.data() : inline_; }
    const T* data() const { return on_heap_ ? heap_.data() : inline_; }
    T* begin() { return data(); }
    T* end() { return data() + size(); }
    const T* begin() const { return data(); }
    const T* end() const { return data() + size(); }
    T& operator[](std::size_t i) { return data()[i]; }
    const T& back() const { return data()[size() - 1]; }

    void push_back(T x)
    {
        if (on_heap_) {
            heap_.push_back(x);
        } else if (n_ < inline_capacity) {
            inline_[n_++] = x;
        } else {
            heap_.assign(inline_, inline_ + n_);
            heap_.push_back(x);
            on_heap_ = true;
        }
    }
    // Keeps the first k components (k <= size()).
    void shrink_to(std::size_t k)
    {
        if (on_heap_) heap_.resize(k);
        else n_ = k;
    }
    void clear() { shrink_to(0); }

private:
    void copy_inline(const Components& o)
    {
        if (!o.on_heap_) std::copy(o.inline_, o.inline_ + o.n_, inline_);
    }

    T inline_[inline_capacity];
    std::size_t n_ = 0;
    bool on_heap_ = false;
    std::vector<T> heap_;
};

template <class T>
class Expansion {
public:
    Expansion() = default;
    Expansion(T x)  // NOLINT(google-explicit-constructor): numbers convert implicitly, as for Bounded
    {
        exact_ = std::abs(x) <= std::numeric_limits<T>::max();
        if (x != T(0) && exact_) c_.push_back(x);
    }

    // False once an input was not finite, a product or sum left T's range on the way here, or the
    // expansion grew beyond max_components: its value is then lost (no components), and the
    // caller turns to Dyadic.
    bool exact() const { return exact_; }

    int sign() const { return c_.empty() ? 0 : (c_.back() > T(0) ? 1 : -1); }
    T estimate() const
    {
        T s = T(0);
        for (T x : c_) s += x;
        return s;
    }
    std::size_t size() const { return c_.size(); }
    // The components, increasing in magnitude, their sum the exact value (tests, diagnostics).
    const T* begin() const { return c_.begin(); }
    const T* end() const { return c_.end(); }

    friend Expansion operator+(const Expansion& a, const Expansion& b)
    {
        if (!a.exact_ || !b.exact_) return given_up();
        Expansion r = sum(a, b);
        r.compress();
        r.exact_ = r.exact_ && a.exact_ && b.exact_;
        return r;
    }
    friend Expansion operator-(const Expansion& a) { Expansion r = a; for (T& x : r.c_) x = -x; return r; }
    friend Expansion operator-(const Expansion& a, const Expansion& b) { return a + (-b); }
    // The sum of the partial products b·x_i (SCALE-EXPANSION of the longer by each component x_i
    // of the shorter), each added in one linear pass.
    friend Expansion operator*(const Expansion& a, const Expansion& b)
    {
        if (!a.exact_ || !b.exact_) return given_up();
        const Expansion& big = a.size() >= b.size() ? a : b;
        const Expansion& small = a.size() >= b.size() ? b : a;
        Expansion r;
        for (T x : small.c_) {
            Expansion partial = scaled(big, x);
            const bool exact = r.exact_ && partial.exact_;
            r = r.c_.empty() ? std::move(partial) : sum(r, partial);
            r.compress();
            r.exact_ = r.exact_ && exact;
        }
        r.exact_ = r.exact_ && a.exact_ && b.exact_;
        return r;
    }
    friend Expansion& operator+=(Expansion& a, const Expansion& b) { return a = a + b; }

private:
    static constexpr std::size_t max_components = 32;

    // An expansion that is no longer exact keeps no components: what follows it costs nothing.
    static Expansion given_up()
    {
        Expansion r;
        r.exact_ = false;
        return r;
    }

    // LINEAR-EXPANSION-SUM with zero elimination (Shewchuk, Theorem 13; round-to-nearest-even):
    // e + f for nonoverlapping e and f, nonoverlapping and increasing, in one pass over their
    // components merged by magnitude. (Two-Sum stands where Shewchuk's proof allows Fast-Two-Sum:
    // the same results.)
    static Expansion sum(const Expansion& e, const Expansion& f)
    {
        const std::size_t ne = e.size(), nf = f.size();
        if (ne == 0) return f;
        if (nf == 0) return e;
        std::size_t i = 0, j = 0;
        // The next component by increasing magnitude.
        const auto next = [&]() {
            const bool take_e = j >= nf || (i < ne && std::abs(e.c_.data()[i]) < std::abs(f.c_.data()[j]));
            return take_e ? e.c_.data()[i++] : f.c_.data()[j++];
        };
        Expansion h;
        const T g0 = next();
        Pair<T> qq = two_sum(next(), g0);  // (Q, q)
        for (std::size_t count = 2; count < ne + nf; ++count) {
            const Pair<T> r = two_sum(next(), qq.lo);
            if (r.lo != T(0)) h.c_.push_back(r.lo);
            qq = two_sum(qq.hi, r.hi);
        }
        if (qq.lo != T(0)) h.c_.push_back(qq.lo);
        if (qq.hi != T(0)) h.c_.push_back(qq.hi);
        return h;
    }
    // SCALE-EXPANSION with zero elimination (Shewchuk, Theorem 19): e·b, nonoverlapping and
    // increasing, in one pass.
    static Expansion scaled(const Expansion& e, T b)
    {
        Expansion h;
        if (e.c_.empty() || b == T(0)) return h;
        // Two-Product is exact when |p| >= 2^(min_exponent − 1 + digits) (its error term's last bit
        // is then representable) and, without FMA, no factor overflows Veltkamp's split (eft.hpp).
        using limits = std::numeric_limits<T>;
        const T tiny = std::ldexp(T(1), limits::min_exponent - 1 + limits::digits);
        const T huge = std::ldexp(T(1), limits::max_exponent - limits::digits / 2 - 2);
        const auto product = [&](T x) {
            const Pair<T> p = two_product(x, b);
            const T m = std::abs(p.hi);
            h.exact_ = h.exact_ && m >= tiny && m <= limits::max() && std::abs(x) <= huge && std::abs(b) <= huge;
            return p;
        };
        const Pair<T> first = product(e.c_.data()[0]);
        if (first.lo != T(0)) h.c_.push_back(first.lo);
        T q = first.hi;
        for (std::size_t i = 1; i < e.size(); ++i) {
            const Pair<T> p = product(e.c_.data()[i]);
            const Pair<T> s = two_sum(q, p.lo);
            if (s.lo != T(0)) h.c_.push_back(s.lo);
            const Pair<T> t = two_sum(p.hi, s.hi);
            if (t.lo != T(0)) h.c_.push_back(t.lo);
            q = t.hi;
        }
        if (q != T(0)) h.c_.push_back(q);
        return h;
    }
    // COMPRESS: the same value in as few components as possible; the largest keeps the sign. In
    // place: the downward pass writes only slots it has read, the upward pass writes below the
    // slot it reads.
    void compress()
    {
        const int n = static_cast<int>(c_.size());
        T* h = c_.data();
        // A sum that overflowed left an infinity or NaN, which the largest component carries on.
        if (n > 0) exact_ = exact_ && std::abs(h[n - 1]) <= std::numeric_limits<T>::max();
        if (n < 2) return;
        int bottom = n - 1;
        T q = h[n - 1];
        for (int i = n - 2; i >= 0; --i) {
            const T sum = q + h[i];
            const T err = h[i] - (sum - q);  // fast two-sum: |q| >= |c_i| holds here
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
        c_.shrink_to(static_cast<std::size_t>(top));
        if (top == 1 && c_[0] == T(0)) c_.clear();
        // So many components mean inputs whose exponents span thousands of bits (1e9 beside
        // 2^-1000): products then cost the square of the length, and a cone's discriminant took
        // seconds (the axial edge cases under RAYQ_FUZZ_STRICT). Dyadic's limbs are cheaper there:
        // give up, and let the caller evaluate again in Dyadic.
        if (c_.size() > max_components) exact_ = false;
        if (!exact_) c_.clear();
    }

    Components<T> c_;  // increasing magnitude, no zeros
    bool exact_ = true;
};

}  // namespace rayq::detail
