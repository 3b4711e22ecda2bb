#include "sampler/sobol.h"

#include <stdexcept>

#include "sampler/hashing.h"

namespace snell {

SobolSampler::SobolSampler(int sample_count, uint64_t seed) : m_count(sample_count), m_seed(seed) {
    if (sample_count <= 0) throw std::invalid_argument("sobol sampler: sample_count must be positive");
}

void SobolSampler::start_pixel_sample(int px, int py, uint64_t index) {
    m_pixel = sample_hash(pixel_hash(m_seed, px, py), index >> 32);
    m_index = uint32_t(index);
    m_dim = 0;
}

uint64_t SobolSampler::next_dimension_hash() { return sample_hash(m_pixel, m_dim++); }

double SobolSampler::next_1d() {
    const uint64_t h = next_dimension_hash();
    const uint32_t i = shuffle_index(m_index, 32, sample_hash(h, 1));
    const uint32_t x = owen_scramble(zero_two_x(i), sample_hash(h, 2));
    // Digits past the 32nd: random per point, as a full Owen scramble would make them.
    return fraction_32(x, sample_hash(h, 4, i));
}

Vec2 SobolSampler::next_2d() {
    const uint64_t h = next_dimension_hash();
    const uint32_t i = shuffle_index(m_index, 32, sample_hash(h, 1));
    const uint32_t x = owen_scramble(zero_two_x(i), sample_hash(h, 2));
    const uint32_t y = owen_scramble(zero_two_y(i), sample_hash(h, 3));
    const uint64_t low = sample_hash(h, 4, i);
    return {fraction_32(x, low), fraction_32(y, low >> 21)};
}

}  // namespace snell
