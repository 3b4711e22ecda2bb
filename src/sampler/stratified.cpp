#include "sampler/stratified.h"

#include <algorithm>
#include <stdexcept>

#include "sampler/hashing.h"

namespace snell {

int StratifiedSampler::round_sample_count(int requested) {
    if (requested <= 0) throw std::invalid_argument("stratified sampler: sample_count must be positive");
    if (requested > (1 << 30)) throw std::invalid_argument("stratified sampler: sample_count must be at most 2^30");
    int res = 1;
    while (res * res < requested) ++res;
    return res * res;
}

StratifiedSampler::StratifiedSampler(int sample_count, uint64_t seed, bool jitter)
    : m_count(uint32_t(round_sample_count(sample_count))), m_res(1), m_seed(seed), m_jitter(jitter) {
    while (m_res * m_res < m_count) ++m_res;
}

void StratifiedSampler::start_pixel_sample(int px, int py, uint64_t index) {
    m_pixel = pixel_hash(m_seed, px, py);
    m_block = index / m_count;
    m_local = uint32_t(index % m_count);
    m_dim = 0;
}

uint64_t StratifiedSampler::hash_dim(uint32_t dim) const { return sample_hash(m_pixel, m_block, dim); }

double StratifiedSampler::next_1d() {
    const uint64_t h = next_dimension_hash();
    const uint32_t stratum = permute_index(m_local, m_count, h);
    const double j = m_jitter ? jitter_32(sample_hash(h, m_local)) : 0.5;
    return std::min((stratum + j) / m_count, kOneMinusEpsilon);
}

Vec2 StratifiedSampler::next_2d() {
    const uint64_t h = next_dimension_hash();
    const uint32_t cell = permute_index(m_local, m_count, h);
    double jx = 0.5, jy = 0.5;
    if (m_jitter) {
        const uint64_t hj = sample_hash(h, m_local);
        jx = jitter_32(hj);
        jy = jitter_32(hj << 32);
    }
    return {std::min((cell % m_res + jx) / m_res, kOneMinusEpsilon),
            std::min((cell / m_res + jy) / m_res, kOneMinusEpsilon)};
}

}  // namespace snell
