#pragma once
// A sum of doubles whose value does not depend on the order of its terms (issue 27). A frame
// rendered on one thread, on many, over MPI ranks or as farm tasks merged afterwards adds the
// same samples in different orders; floating-point addition is not associative, so only an
// exact sum gives the same image bit for bit. Each term is rounded once, towards zero, to a
// multiple of 2^-kFractionBits and added into a 192-bit two's-complement integer: integer
// addition is associative, so any grouping of the same terms gives the same bits.
#include <array>
#include <cmath>
#include <cstdint>

namespace snell {

class ExactSum {
public:
    /// Terms are kept to 2^-80 (about 8e-25): far below any radiance a scene in physical units
    /// or in display units produces, and below float's resolution of every pixel value but
    /// those under 1e-17.
    static constexpr int kFractionBits = 80;
    /// Terms of at least this magnitude (2^80, about 1.2e24) are saturated to it (and counted
    /// by the caller): 2^30 samples (the largest --spp) of that size still fit the 192 bits.
    static constexpr double kMaxTerm = 1208925819614629174706176.0;  // 2^80

    ExactSum() = default;
    explicit ExactSum(double v) { add(v); }

    /// Adds v (NaN adds nothing; |v| >= kMaxTerm adds kMaxTerm with v's sign). Returns false when
    /// v was saturated or NaN.
    bool add(double v) {
        if (!(v == v)) return false;
        const bool saturated = !(std::abs(v) < kMaxTerm);
        if (saturated) v = v < 0 ? -kMaxTerm : kMaxTerm;
        if (v == 0) return !saturated;
        int e = 0;
        const double f = std::frexp(std::abs(v), &e);    // |v| = f 2^e, f in [0.5, 1)
        const uint64_t m = uint64_t(std::ldexp(f, 53));  // exact: a 53-bit integer
        const int shift = e - 53 + kFractionBits;        // |v| 2^80 = m 2^shift
        std::array<uint64_t, 3> t{0, 0, 0};
        if (shift < 0) {
            if (shift > -64) t[0] = m >> -shift;  // truncated: the bits below 2^-80 go
        } else {
            const int limb = shift / 64, bit = shift % 64;  // shift <= 107: limb <= 1
            t[size_t(limb)] = m << bit;
            if (bit > 0) t[size_t(limb) + 1] = m >> (64 - bit);
        }
        if (v < 0) negate(t);
        add_limbs(t);
        return !saturated;
    }
    ExactSum& operator+=(const ExactSum& o) {
        add_limbs(o.m_limbs);
        return *this;
    }
    bool operator==(const ExactSum& o) const { return m_limbs == o.m_limbs; }
    bool operator!=(const ExactSum& o) const { return !(*this == o); }

    /// The sum, rounded to the nearest double (the same bits give the same double).
    double value() const {
        std::array<uint64_t, 3> t = m_limbs;
        const bool negative = (t[2] >> 63) != 0;
        if (negative) negate(t);
        const double mag = std::ldexp(double(t[2]), 128) + std::ldexp(double(t[1]), 64) + double(t[0]);
        return std::ldexp(negative ? -mag : mag, -kFractionBits);
    }
    /// The 192 bits, least significant limb first (partial films store them, issue 27).
    const std::array<uint64_t, 3>& limbs() const { return m_limbs; }
    static ExactSum from_limbs(const std::array<uint64_t, 3>& l) {
        ExactSum s;
        s.m_limbs = l;
        return s;
    }

private:
    static void negate(std::array<uint64_t, 3>& t) {
        uint64_t carry = 1;
        for (uint64_t& l : t) {
            l = ~l + carry;
            carry = carry && l == 0;
        }
    }
    void add_limbs(const std::array<uint64_t, 3>& t) {
        uint64_t carry = 0;
        for (size_t i = 0; i < 3; ++i) {
            const uint64_t a = m_limbs[i], s = a + t[i];
            const uint64_t r = s + carry;
            carry = uint64_t(s < a) + uint64_t(r < s);
            m_limbs[i] = r;
        }
    }
    std::array<uint64_t, 3> m_limbs{0, 0, 0};
};

/// Three exact sums: a pixel's X, Y and Z.
struct ExactSum3 {
    ExactSum x, y, z;
    ExactSum3& operator+=(const ExactSum3& o) {
        x += o.x;
        y += o.y;
        z += o.z;
        return *this;
    }
    bool operator==(const ExactSum3& o) const { return x == o.x && y == o.y && z == o.z; }
};

}  // namespace snell
