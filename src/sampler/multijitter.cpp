#include "sampler/multijitter.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sampler/hashing.h"

namespace snell {

void MultiJitterSampler::grid_for(int requested, int& cols, int& rows) {
    if (requested <= 0) throw std::invalid_argument("multijitter sampler: sample_count must be positive");
    if (requested > (1 << 30)) throw std::invalid_argument("multijitter sampler: sample_count must be at most 2^30");
    const int64_t n = requested;
    // An exact factorisation with aspect ratio at most 2, largest rows first.
    for (int64_t r = int64_t(std::sqrt(double(n))) + 1; r >= 1; --r) {
        if (r * r > n || n % r != 0) continue;
        if (2 * r * r < n) break;
        rows = int(r);
        cols = int(n / r);
        return;
    }
    // Mitsuba 2's rule: rows = floor(sqrt(n)), cols = ceil(n / rows).
    int64_t r = int64_t(std::sqrt(double(n)));
    while (r * r > n) --r;
    while ((r + 1) * (r + 1) <= n) ++r;
    rows = int(r);
    cols = int((n + r - 1) / r);
}

int MultiJitterSampler::round_sample_count(int requested) {
    int cols = 1, rows = 1;
    grid_for(requested, cols, rows);
    return cols * rows;
}

MultiJitterSampler::MultiJitterSampler(int sample_count, uint64_t seed, bool jitter) : m_seed(seed), m_jitter(jitter) {
    int cols = 1, rows = 1;
    grid_for(sample_count, cols, rows);
    m_cols = uint32_t(cols);
    m_rows = uint32_t(rows);
    m_count = m_cols * m_rows;
}

void MultiJitterSampler::start_pixel_sample(int px, int py, uint64_t index) {
    m_pixel = pixel_hash(m_seed, px, py);
    m_block = index / m_count;
    m_local = uint32_t(index % m_count);
    m_dim = 0;
}

uint64_t MultiJitterSampler::next_dimension_hash() { return sample_hash(m_pixel, m_block, m_dim++); }

double MultiJitterSampler::next_1d() {
    const uint64_t h = next_dimension_hash();
    const uint32_t stratum = permute_index(m_local, m_count, h);
    const double j = m_jitter ? jitter_32(sample_hash(h, m_local)) : 0.5;
    return std::min((stratum + j) / m_count, kOneMinusEpsilon);
}

Vec2 MultiJitterSampler::next_2d() {
    const uint64_t h = next_dimension_hash();
    // Kensler 2013, Listing 3: the point's cell (col, row) in a shuffled order, then its sub-stratum
    // inside the cell from one permutation shared by all rows (sx) and one by all columns (sy).
    const uint32_t s = permute_index(m_local, m_count, sample_hash(h, 1));
    const uint32_t col = s % m_cols, row = s / m_cols;
    const uint32_t sx = permute_index(col, m_cols, sample_hash(h, 2));
    const uint32_t sy = permute_index(row, m_rows, sample_hash(h, 3));
    double jx = 0.5, jy = 0.5;
    if (m_jitter) {
        const uint64_t hj = sample_hash(h, 4, m_local);
        jx = jitter_32(hj);
        jy = jitter_32(hj << 32);
    }
    // x = (col + (sy + jx) / rows) / cols and y = (row + (sx + jy) / cols) / rows, written with one
    // exact numerator each: the 1D stratum of x is col * rows + sy, that of y is row * cols + sx.
    return {std::min((double(col * m_rows + sy) + jx) / m_count, kOneMinusEpsilon),
            std::min((double(row * m_cols + sx) + jy) / m_count, kOneMinusEpsilon)};
}

}  // namespace snell
