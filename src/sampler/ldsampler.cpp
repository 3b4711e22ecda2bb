#include "sampler/ldsampler.h"

#include <bit>
#include <stdexcept>

#include "sampler/hashing.h"

namespace snell {

int LowDiscrepancySampler::round_sample_count(int requested) {
    if (requested <= 0) throw std::invalid_argument("ldsampler: sample_count must be positive");
    if (requested > (1 << 30)) throw std::invalid_argument("ldsampler: sample_count must be at most 2^30");
    int n = 4;
    while (n < requested) n *= 4;
    return n;
}

LowDiscrepancySampler::LowDiscrepancySampler(int sample_count, uint64_t seed)
    : m_count(uint32_t(round_sample_count(sample_count))), m_log2_count(std::countr_zero(m_count)), m_seed(seed) {}

void LowDiscrepancySampler::start_pixel_sample(int px, int py, uint64_t index) {
    m_pixel = pixel_hash(m_seed, px, py);
    m_block = index / m_count;
    m_local = uint32_t(index % m_count);
    m_dim = 0;
}

uint64_t LowDiscrepancySampler::next_dimension_hash() { return sample_hash(m_pixel, m_block, m_dim++); }

double LowDiscrepancySampler::next_1d() {
    const uint64_t h = next_dimension_hash();
    const uint32_t i = shuffle_index(m_local, m_log2_count, sample_hash(h, 1));
    const uint64_t scramble = sample_hash(h, 2);
    return fraction_32(zero_two_x(i) ^ uint32_t(scramble), scramble >> 32);
}

Vec2 LowDiscrepancySampler::next_2d() {
    const uint64_t h = next_dimension_hash();
    const uint32_t i = shuffle_index(m_local, m_log2_count, sample_hash(h, 1));
    const uint64_t sx = sample_hash(h, 2), sy = sample_hash(h, 3);
    return {fraction_32(zero_two_x(i) ^ uint32_t(sx), sx >> 32), fraction_32(zero_two_y(i) ^ uint32_t(sy), sy >> 32)};
}

}  // namespace snell
