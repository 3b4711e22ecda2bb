#include "integrators/mnee/connection_allocation.h"

#include <algorithm>
#include <cmath>

namespace snell {

namespace {

int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

double finite_or_zero(double v) { return std::isfinite(v) ? v : 0.0; }

}  // namespace

void PilotSample::add_path(double f, double p_m, double p_other, double q_pilot) {
    if (!(f > 0) || !std::isfinite(f) || !(p_m > 0)) return;
    if (!(p_other > 0)) needs_mnee = true;
    // Every pilot sample of every technique estimates the integral of g over the refracted
    // paths as g / (q_pilot p_m + p_other) (the balance heuristic's combination of the pilot's
    // own techniques), so the techniques that find a path rarely are judged by the samples of
    // those that find it often: with g = f^2 / (q p_m + p_other), the balance heuristic's
    // second moment at q.
    const double pilot = q_pilot * p_m + p_other;
    for (int j = 0; j < kCandidateCount; ++j) {
        const double mix = kConnectCandidates[size_t(j)] * p_m + p_other;
        if (mix > 0) m2[size_t(j)] += finite_or_zero(f * f / (mix * pilot));
    }
    m2_pilot += finite_or_zero(f * f / (pilot * pilot));
}

void PilotSample::add_connection(double value, double p_m, double p_other, double q_pilot) {
    add_path(value * p_m, p_m, p_other, q_pilot);
}

void PilotSample::add_other(double value, double p_t, double p_m, double p_other, double q_pilot) {
    add_path(value * p_t, p_m, p_other, q_pilot);
}

ConnectionAllocation::ConnectionAllocation(int width, int height, int crop_x, int crop_y, int block, double q_pilot)
    : m_width(width),
      m_height(height),
      m_crop_x(crop_x),
      m_crop_y(crop_y),
      m_block(std::max(1, block)),
      m_q_pilot(q_pilot),
      m_pixels(size_t(std::max(0, width)) * size_t(std::max(0, height))) {
    m_rx0 = floor_div(crop_x, m_block);
    m_ry0 = floor_div(crop_y, m_block);
    m_rw = floor_div(crop_x + width - 1, m_block) - m_rx0 + 1;
    m_rh = floor_div(crop_y + height - 1, m_block) - m_ry0 + 1;
    m_choice.assign(size_t(std::max(0, m_rw)) * size_t(std::max(0, m_rh)), int8_t(-1));
}

int ConnectionAllocation::region_of(int x, int y) const {
    const int rx = floor_div(x, m_block) - m_rx0, ry = floor_div(y, m_block) - m_ry0;
    if (rx < 0 || ry < 0 || rx >= m_rw || ry >= m_rh) return -1;
    return ry * m_rw + rx;
}

int ConnectionAllocation::choice(int x, int y) const {
    const int r = region_of(x, y);
    return m_fitted && r >= 0 ? m_choice[size_t(r)] : -1;
}

double ConnectionAllocation::q(int x, int y) const {
    const int c = choice(x, y);
    return c < 0 ? m_q_pilot : kConnectCandidates[size_t(c)];
}

void ConnectionAllocation::add(int x, int y, const PilotSample& s, double value, double work) {
    const int lx = x - m_crop_x, ly = y - m_crop_y;
    if (m_fitted || lx < 0 || ly < 0 || lx >= m_width || ly >= m_height) return;
    PixelStats& p = m_pixels[size_t(ly) * size_t(m_width) + size_t(lx)];
    bool finite = std::isfinite(value) && std::isfinite(s.m2_pilot);
    for (double m : s.m2) finite = finite && std::isfinite(m);
    if (!finite) return;  // the film drops such a sample too
    for (int j = 0; j < kCandidateCount; ++j) p.m2[size_t(j)] += s.m2[size_t(j)];
    p.m2_pilot += s.m2_pilot;
    p.sum += value;
    p.sum2 += value * value;
    p.work += work;
    p.work_connect += s.work_connect;
    p.work_density += s.work_density;
    p.needs_mnee = p.needs_mnee || s.needs_mnee;
    ++p.n;
}

void ConnectionAllocation::widen_to_regions(int& x0, int& y0, int& x1, int& y1) const {
    const auto widen = [&](int& a, int& b, int offset, int size) {
        a = std::max(0, floor_div(a + offset, m_block) * m_block - offset);
        b = std::min(size, (floor_div(b - 1 + offset, m_block) + 1) * m_block - offset);
    };
    widen(x0, x1, m_crop_x, m_width);
    widen(y0, y1, m_crop_y, m_height);
}

namespace {
constexpr size_t kPilotValues = kCandidateCount + 8;  // PixelStats as doubles
}  // namespace

std::vector<double> ConnectionAllocation::pilot_state() const {
    std::vector<double> v(m_pixels.size() * kPilotValues, 0.0);
    for (size_t i = 0; i < m_pixels.size(); ++i) {
        const PixelStats& p = m_pixels[i];
        double* d = v.data() + i * kPilotValues;
        for (int j = 0; j < kCandidateCount; ++j) d[j] = p.m2[size_t(j)];
        d += kCandidateCount;
        d[0] = p.m2_pilot;
        d[1] = p.sum;
        d[2] = p.sum2;
        d[3] = p.work;
        d[4] = p.work_connect;
        d[5] = p.work_density;
        d[6] = double(p.n);
        d[7] = p.needs_mnee ? 1.0 : 0.0;
    }
    return v;
}

void ConnectionAllocation::set_pilot_state(const std::vector<double>& v) {
    if (v.size() != m_pixels.size() * kPilotValues) return;
    for (size_t i = 0; i < m_pixels.size(); ++i) {
        PixelStats& p = m_pixels[i];
        const double* d = v.data() + i * kPilotValues;
        for (int j = 0; j < kCandidateCount; ++j) p.m2[size_t(j)] = d[j];
        d += kCandidateCount;
        p.m2_pilot = d[0];
        p.sum = d[1];
        p.sum2 = d[2];
        p.work = d[3];
        p.work_connect = d[4];
        p.work_density = d[5];
        p.n = uint32_t(d[6]);
        p.needs_mnee = d[7] > 0;
    }
}

void ConnectionAllocation::fit() {
    if (m_fitted) return;
    const size_t regions = m_choice.size();
    std::vector<std::array<double, kCandidateCount>> variance(regions), work(regions);
    std::vector<bool> needs_mnee(regions, false);
    for (auto& v : variance) v.fill(0.0);
    for (auto& w : work) w.fill(0.0);
    // Raster order: each region sums its own pixels row by row, in a crop as in the full film.
    for (int ly = 0; ly < m_height; ++ly)
        for (int lx = 0; lx < m_width; ++lx) {
            const PixelStats& p = m_pixels[size_t(ly) * size_t(m_width) + size_t(lx)];
            if (p.n == 0) continue;
            const size_t r = size_t(region_of(lx + m_crop_x, ly + m_crop_y));
            const double n = p.n;
            // Per-sample variance under q: the pilot's second moment with the refracted paths'
            // share replaced by theirs under q, less the squared mean (unbiased estimate).
            const double mean2 = p.n > 1 ? (p.sum * p.sum - p.sum2) / (n * (n - 1)) : 0.0;
            const double rest = (p.sum2 - p.m2_pilot) / n - mean2;
            const double work_rest = (p.work - p.work_connect - p.work_density) / n;
            for (int j = 0; j < kCandidateCount; ++j) {
                const double q = kConnectCandidates[size_t(j)];
                variance[r][size_t(j)] += rest + p.m2[size_t(j)] / n;
                work[r][size_t(j)] += work_rest + (q / m_q_pilot * p.work_connect + (q > 0 ? p.work_density : 0.0)) / n;
            }
            needs_mnee[r] = needs_mnee[r] || p.needs_mnee;
        }
    for (size_t r = 0; r < regions; ++r) {
        const auto& v = variance[r];
        const double vmax = *std::max_element(v.begin(), v.end());
        int best = -1;
        double best_cost = 0;
        for (int j = needs_mnee[r] ? 1 : 0; j < kCandidateCount; ++j) {
            // Variance x work is the inverse efficiency; where the pilot saw no variance at all
            // (a black region) the work alone decides.
            const double var = vmax > 0 ? std::max(v[size_t(j)], 1e-9 * vmax) : 1.0;
            const double cost = var * work[r][size_t(j)];
            if (best < 0 || cost < best_cost) {
                best = j;
                best_cost = cost;
            }
        }
        m_choice[r] = int8_t(best);
    }
    m_fitted = true;
    m_pixels = {};
}

std::array<uint64_t, kCandidateCount> ConnectionAllocation::histogram() const {
    std::array<uint64_t, kCandidateCount> h{};
    for (int8_t c : m_choice)
        if (c >= 0) ++h[size_t(c)];
    return h;
}

}  // namespace snell
