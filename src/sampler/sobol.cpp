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
    m_index_reversed = reverse_bits(m_index);
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

// The same points as owen_scramble(zero_two_x(shuffle_index(...))) and friends, with the bit
// reversals that cancel left out: shuffle_index(i) = R(S_h(R(i))) for 32 bits, and
// owen_scramble(v) = R(S(R(v))), where R reverses bits and S is owen_scramble_reversed.
uint32_t SobolSampler::shuffled_index(uint64_t h) const {
    return reverse_bits(owen_scramble_reversed(m_index_reversed, h));
}

double SobolSampler::next_1d() {
    const uint64_t h = next_dimension_hash();
    const uint32_t i = shuffled_index(h);
    const uint32_t x = reverse_bits(owen_scramble_reversed(i, h * kKey2));  // zero_two_x(i) = R(i)
    // Digits past the 32nd: random per point, as a full Owen scramble would make them.
    return fraction_32(x, (h ^ (uint64_t(i) * kKey3)) * kKey3);
}

Vec2 SobolSampler::next_2d() {
    const uint64_t h = next_dimension_hash();
    const uint32_t i = shuffled_index(h);
    const uint32_t x = reverse_bits(owen_scramble_reversed(i, h * kKey2));
    const uint32_t y = reverse_bits(owen_scramble_reversed(zero_two_y<true>(i), h * kKey3));
    const uint64_t low = (h ^ (uint64_t(i) * kKey3)) * kKey2;
    return {fraction_32(x, low), fraction_32(y, low >> 21)};
}

}  // namespace snell
