#pragma once
#include <array>
#include <bit>
#include <cstdint>

#include "core/rng.h"

namespace snell {

/// Hashing shared by the pixel samplers: every random decision of a sampler (a permutation, a
/// scramble, a jitter) is a hash of (seed, pixel, sample block, dimension), never RNG state, so a
/// pixel sample's stream is a pure function of (seed, pixel, index).

/// The largest double below 1; samplers clamp to it so that every value lies in [0, 1).
inline constexpr double kOneMinusEpsilon = 0x1.fffffffffffffp-1;

/// Folds `v` into the running hash `h` (order matters: hash_combine(a, b) != hash_combine(b, a)).
inline uint64_t hash_combine(uint64_t h, uint64_t v) {
    return mix_bits(h ^ mix_bits(v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2)));
}

/// Hash of any number of integer keys.
template <typename... Ts>
uint64_t sample_hash(uint64_t first, Ts... rest) {
    uint64_t h = mix_bits(first ^ 0x6a09e667f3bcc909ULL);
    ((h = hash_combine(h, uint64_t(rest))), ...);
    return h;
}

/// Hash of the seed and pixel; the per-pixel randomisation of every sampler starts from it.
inline uint64_t pixel_hash(uint64_t seed, int px, int py) { return sample_hash(seed, uint32_t(px), uint32_t(py)); }

/// Uniform in [0, 1) from the top 32 bits of a hash. A 32-bit jitter keeps `stratum + jitter`
/// exact in a double, so a jittered point can never round into the next stratum.
inline double jitter_32(uint64_t h) { return double(uint32_t(h >> 32)) * 0x1.0p-32; }

/// A 32-bit binary fraction (digit 1 is the top bit) extended by 21 low bits from `low`, as a
/// double in [0, 1). The low bits fill in the double's mantissa and do not touch the first 32
/// digits, so nets and strata of the 32-bit value are preserved.
inline double fraction_32(uint32_t digits, uint64_t low) {
    return double((uint64_t(digits) << 21) | (low & 0x1fffffULL)) * 0x1.0p-53;
}

constexpr uint32_t reverse_bits(uint32_t v) {
    v = __builtin_bswap32(v);  // std::byteswap is C++23
    v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    return ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
}

/// A pseudo-random permutation of [0, n) chosen by `seed`, evaluated at `i` < n without tables:
/// a bijection of [0, 2^k) (2^k >= n) built from invertible steps (xor with a key, multiply by an
/// odd constant, xorshift, all modulo 2^k), iterated until it lands below n ("cycle walking",
/// Kensler 2013, Sec. 3). Terminates because the orbit of i returns to i.
inline uint32_t permute_index(uint32_t i, uint32_t n, uint64_t seed) {
    if (n <= 1) return 0;
    const int k = std::bit_width(n - 1);
    const uint32_t mask = uint32_t((uint64_t(1) << k) - 1);
    const int shift = k / 2 + 1;
    const uint32_t k0 = uint32_t(seed), k1 = uint32_t(seed >> 32);
    do {
        i = ((i ^ k0) * 0x9e3779b1u) & mask;
        i ^= i >> shift;
        i = ((i + k1) * 0x85ebca77u) & mask;
        i ^= i >> shift;
        i = ((i ^ (k1 >> 7)) * 0xc2b2ae3du) & mask;
        i ^= i >> shift;
    } while (i >= n);
    return i;
}

/// Hash-based Owen scrambling (Burley 2020, "Practical Hash-based Owen Scrambling"): `v` read as a
/// binary fraction, digit j (from the top) is flipped by a pseudo-random function of `seed` and of
/// digits 1..j-1. In the bit-reversed word the top digits are the low bits, and each step below
/// (add a key, multiply by an odd key, xor with a multiple by an even constant) changes bit b only
/// by a function of bits below b, which is exactly a nested (Owen) scramble. Owen scrambling maps
/// every (t, m, s)-net to a (t, m, s)-net, so scrambled Sobol points keep their stratification.
/// owen_scramble_reversed() works on the bit-reversed word directly: the Sobol sampler chains
/// scrambles and keeps its words reversed in between, which saves most of the bit reversals.
inline uint32_t owen_scramble_reversed(uint32_t r, uint64_t seed) {
    const uint32_t k0 = uint32_t(seed), k1 = uint32_t(seed >> 32);
    r += k0;
    r ^= r * 0x6a09e666u;
    r *= k1 | 1u;
    r ^= r * 0xbb67ae84u;
    r += k1 ^ 0x3c6ef372u;
    r ^= r * 0xa54ff53au;
    r *= (k0 >> 1) | 1u;
    r ^= r * 0x510e527eu;
    return r;
}
inline uint32_t owen_scramble(uint32_t v, uint64_t seed) {
    return reverse_bits(owen_scramble_reversed(reverse_bits(v), seed));
}

/// Shuffles the first 2^bits sample indices (0 < bits <= 32) by an Owen scramble of the index
/// read as a `bits`-digit fraction (top digit = highest index bit). Any aligned block of 2^m
/// indices maps onto an aligned block of 2^m indices, so every power-of-two prefix of a (0,2)-
/// sequence stays a (0,m,2)-net after shuffling (Burley 2020, Sec. 4).
inline uint32_t shuffle_index(uint32_t i, int bits, uint64_t seed) {
    if (bits <= 0) return 0;
    return owen_scramble(i << (32 - bits), seed) >> (32 - bits);
}

/// Digits of the (0,2)-sequence in base 2: dimension 0 is the van der Corput sequence (the bit-
/// reversed index), dimension 1 is Sobol's second dimension (generator matrix: Pascal's triangle
/// modulo 2). Both are 32-digit binary fractions; any aligned block of 2^m indices is a (0,m,2)-net.
inline uint32_t zero_two_x(uint32_t i) { return reverse_bits(i); }
/// Sobol's second dimension bit by bit: the reference for zero_two_y's tables.
constexpr uint32_t zero_two_y_bitwise(uint32_t i) {
    uint32_t v = 0x80000000u, y = 0;
    for (; i; i >>= 1, v ^= v >> 1)
        if (i & 1u) y ^= v;
    return y;
}
/// Byte tables of Sobol's second dimension, optionally bit-reversed: the map is linear over
/// GF(2), so y(i) is the xor of the images of i's bytes. Shuffled indices use all 32 bits, where
/// the bitwise loop would take 32 steps. Built at compile time (no guard on the hot path).
template <bool Reversed>
inline constexpr std::array<std::array<uint32_t, 256>, 4> kZeroTwoYTable = [] {
    std::array<std::array<uint32_t, 256>, 4> t{};
    for (uint32_t k = 0; k < 4; ++k)
        for (uint32_t b = 0; b < 256; ++b) {
            const uint32_t y = zero_two_y_bitwise(b << (8 * k));
            t[k][b] = Reversed ? reverse_bits(y) : y;
        }
    return t;
}();
template <bool Reversed = false>
inline uint32_t zero_two_y(uint32_t i) {
    const auto& t = kZeroTwoYTable<Reversed>;
    return t[0][i & 255u] ^ t[1][(i >> 8) & 255u] ^ t[2][(i >> 16) & 255u] ^ t[3][i >> 24];
}

}  // namespace snell
