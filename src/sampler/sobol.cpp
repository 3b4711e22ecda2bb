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

// One hash per dimension; the scrambles' keys are that hash times odd constants (bijections of
// a well-mixed word). The sampler runs for every dimension of every path: hash chains per key
// made it a sixth of `nee`'s time.
namespace {
constexpr uint64_t kKey2 = 0x9e3779b97f4a7c15ULL, kKey3 = 0xc2b2ae3d27d4eb4fULL;
uint64_t key(uint64_t h, uint64_t k) { return mix_bits(h ^ (k * 0xd6e8feb86659fd93ULL)); }
}  // namespace

uint64_t SobolSampler::next_dimension_hash() { return key(m_pixel, 0x100000000ULL + m_dim++); }

double SobolSampler::next_1d() {
    const uint64_t h = next_dimension_hash();
    const uint32_t i = shuffle_index(m_index, 32, h);
    const uint32_t x = owen_scramble(zero_two_x(i), h * kKey2);
    // Digits past the 32nd: random per point, as a full Owen scramble would make them.
    return fraction_32(x, (h ^ (uint64_t(i) * kKey3)) * kKey3);
}

Vec2 SobolSampler::next_2d() {
    const uint64_t h = next_dimension_hash();
    const uint32_t i = shuffle_index(m_index, 32, h);
    const uint32_t x = owen_scramble(zero_two_x(i), h * kKey2);
    const uint32_t y = owen_scramble(zero_two_y(i), h * kKey3);
    const uint64_t low = (h ^ (uint64_t(i) * kKey3)) * kKey2;
    return {fraction_32(x, low), fraction_32(y, low >> 21)};
}

}  // namespace snell
