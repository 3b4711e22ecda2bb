#include "sampler/orthogonal.h"

#include <algorithm>
#include <stdexcept>

#include "sampler/hashing.h"

namespace snell {

namespace {

bool is_prime(int n) {
    if (n < 2) return false;
    for (int d = 2; d * d <= n; ++d)
        if (n % d == 0) return false;
    return true;
}

}  // namespace

int OrthogonalSampler::prime_for(int requested) {
    if (requested <= 0) throw std::invalid_argument("orthogonal sampler: sample_count must be positive");
    if (requested > (1 << 30)) throw std::invalid_argument("orthogonal sampler: sample_count must be at most 2^30");
    int p = 2;
    while (p * p < requested || !is_prime(p)) ++p;
    return p;
}

OrthogonalSampler::OrthogonalSampler(int sample_count, uint64_t seed, bool jitter)
    : m_p(uint32_t(prime_for(sample_count))), m_seed(seed), m_jitter(jitter) {}

void OrthogonalSampler::start_pixel_sample(int px, int py, uint64_t index) {
    const uint32_t n = m_p * m_p;
    m_pixel = pixel_hash(m_seed, px, py);
    m_block = index / n;
    m_local = uint32_t(index % n);
    // The point order is shuffled per pixel and block; its digits then index the OA's row.
    const uint32_t row = permute_index(m_local, n, sample_hash(m_pixel, m_block, 0xA11CEull));
    m_a = row / m_p;
    m_b = row % m_p;
    m_round = 0;
    m_col = 0;
    m_round_hash = sample_hash(m_pixel, m_block, m_round);
}

uint32_t OrthogonalSampler::column(uint32_t j) const {
    // Bose: columns a, b, a + b, a + 2b, ... (mod p); their values permuted per column.
    const uint32_t v = j == 0 ? m_a : j == 1 ? m_b : (m_a + (j - 1) * m_b) % m_p;
    return permute_index(v, m_p, sample_hash(m_round_hash, j, 1));
}

double OrthogonalSampler::coordinate(uint32_t j) const {
    const uint32_t stratum = column(j);
    // The sub-stratum from the next column (cyclically), which takes each of its p values once
    // among the points of this stratum; permuted per column (correlated, as in Kensler's CMJ).
    const uint32_t next = (j + 1) % (m_p + 1);
    const uint32_t sub = permute_index(column(next), m_p, sample_hash(m_round_hash, j, 2));
    const double jit = m_jitter ? jitter_32(sample_hash(m_round_hash, j, 3, m_local)) : 0.5;
    return std::min((double(stratum * m_p + sub) + jit) / double(m_p * m_p), kOneMinusEpsilon);
}

uint32_t OrthogonalSampler::take_columns(uint32_t need) {
    if (m_col + need > m_p + 1) {
        ++m_round;
        m_col = 0;
        m_round_hash = sample_hash(m_pixel, m_block, m_round);
    }
    const uint32_t j = m_col;
    m_col += need;
    return j;
}

double OrthogonalSampler::next_1d() { return coordinate(take_columns(1)); }

Vec2 OrthogonalSampler::next_2d() {
    const uint32_t j = take_columns(2);
    return {coordinate(j), coordinate(j + 1)};
}

}  // namespace snell
