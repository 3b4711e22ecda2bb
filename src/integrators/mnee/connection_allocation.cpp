#include "integrators/mnee/connection_allocation.h"

#include <algorithm>
#include <cmath>

#include "core/vector.h"
#include "integrators/mis.h"

namespace snell {

namespace {

// How many times its region's median pixel mean a pixel may be before its variance counts
// less in the region's choice (fit()).
constexpr double kOutlierLevel = 10.0;
// The image's price of work: a region's median pixel mean counts as at least this fraction of
// the lattice's mean of them, and the price is learned in at most kPriceRounds rounds. 0.3 is
// the best of the floors measured (docs/experiments.md, eleventh measurement).
constexpr double kRelativeFloor = 0.3;
constexpr int kPriceRounds = 20;

int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

double finite_or_zero(double v) { return std::isfinite(v) ? v : 0.0; }

// The power heuristic's second moment of a path of integrand f at candidate q, technique by
// technique (PilotSample::add_path): MNEE weighs it by a = q p_m and draws it with density q p_s
// (counted n times), the other techniques with p_other; `pilot` is the pilot's own density of the
// path, over which every pilot sample estimates the other techniques' share.
double second_moment(double f, double n, double a, double q, double p_s, double p_other, double pilot, double q_pilot,
                     bool own) {
    const double sum = a * a + p_other * p_other;
    if (!(sum > 0)) return 0.0;
    double m = n * f * f * p_other * p_other * p_other / (sum * sum * pilot);
    if (own && a > 0) m += n * n * f * f * a * a * a * a / (sum * sum * q * p_s * q_pilot * p_s);
    return finite_or_zero(m);
}

}  // namespace

void PilotSample::add_path(double f, double n, double p_m, double p_s, double p_other, double q_pilot, bool surface,
                           bool own, double realized) {
    if (!(f > 0) || !std::isfinite(f) || !(p_m > 0) || !(p_s > 0)) return;
    if (!(p_other > 0)) needs_mnee = true;
    // The power heuristic's second moment at q, technique by technique: MNEE's share
    // w_m^2 f^2 / (q p_s) (it draws the path with density q p_s, counted N times, and weighs
    // it by q p_m), the other techniques' w_o^2 f^2 / p_other. Every pilot sample, whichever
    // technique drew it, estimates the other techniques' share over the pilot's own density
    // q_pilot p_s + p_other, so that where BSDF sampling rarely finds a path its share is judged
    // from MNEE's samples, which find it often. MNEE's own share comes from its own samples
    // (its counts N are theirs).
    const double pilot = q_pilot * p_s + p_other;
    const auto second = [&](double q, double pm) {
        return second_moment(f, n, q * pm, q, p_s, p_other, pilot, q_pilot, own);
    };
    for (int j = 0; j < kCandidateCount; ++j) {
        const double q = kConnectCandidates[size_t(j)];
        m2[size_t(j)] += second(q, p_m);
        // Without surface trials their paths have MNEE density 0.
        m2_no_trials[size_t(j)] += second(q, surface ? 0.0 : p_m);
        m2_failed_walk[size_t(j)] += second(q, p_m);
    }
    if (surface && !(p_other > 0)) needs_trials = true;
    m2_pilot += finite_or_zero(realized * realized);
}

void PilotSample::add_connection(double value, double count, double p_m, double weight, double p_other, double q_pilot,
                                 bool surface) {
    const double p_s = p_m / weight;
    add_path(value / count * p_s, count, p_m, p_s, p_other, q_pilot, surface, /*own=*/true,
             value * power_heuristic(q_pilot * p_m, {p_other}) / q_pilot);
}

void PilotSample::add_other(double value, double p_t, double p_m, double weight, double p_other, double q_pilot,
                            bool surface) {
    add_path(value * p_t, 1.0, p_m, p_m / weight, p_other, q_pilot, surface, /*own=*/false,
             value * power_heuristic(p_t, {q_pilot * p_m, p_other - p_t}));
}

void PilotSample::add_common(double f, double n, double p_s, double p_other, double q_pilot, bool own,
                             double realized) {
    m2_pilot += finite_or_zero(realized * realized);
    if (!(f > 0) || !std::isfinite(f) || !(p_s > 0)) return;
    const double pilot = q_pilot * p_s + p_other;
    for (int j = 0; j < kCandidateCount; ++j) {
        // The third kind gives them to MNEE at density q p_s (weight 1).
        const double q = kConnectCandidates[size_t(j)];
        m2_failed_walk[size_t(j)] += second_moment(f, n, q * p_s, q, p_s, p_other, pilot, q_pilot, own);
    }
    if (!(p_other > 0)) return;
    // BSDF sampling's share, f^2 / p_other, under every other candidate, estimated over the
    // pilot's density of the path (the probes' and the other techniques'): where BSDF sampling
    // finds these paths rarely (near a fold, where the straight walk fails) its own hits are too
    // few in a pilot to show their variance, and the region would take a costly q for nothing.
    const double m = finite_or_zero(n * f * f / (p_other * pilot));
    for (int j = 0; j < kCandidateCount; ++j) {
        m2[size_t(j)] += m;
        m2_no_trials[size_t(j)] += m;
    }
}

void PilotSample::add_probe(double value, double count, double p_s, double p_other, double q_pilot) {
    add_common(value / count * p_s, count, p_s, p_other, q_pilot, /*own=*/true, 0.0);
}

void PilotSample::add_probe_other(double value, double p_t, double p_s, double p_other, double q_pilot) {
    add_common(value * p_t, 1.0, p_s, p_other, q_pilot, /*own=*/false, value * power_heuristic(p_t, {p_other - p_t}));
}

ConnectionAllocation::ConnectionAllocation(int width, int height, int crop_x, int crop_y, int block, double q_pilot,
                                           TrialAllocation trials, WorkPrice price, bool failed_walk_kind)
    : m_width(width),
      m_height(height),
      m_crop_x(crop_x),
      m_crop_y(crop_y),
      m_block(std::max(1, block)),
      m_q_pilot(q_pilot),
      m_trial_allocation(trials),
      m_price(price),
      m_failed_walk_kind(failed_walk_kind && trials == TrialAllocation::Learned),
      m_pixels(size_t(std::max(0, width)) * size_t(std::max(0, height))) {
    m_rx0 = floor_div(crop_x, m_block);
    m_ry0 = floor_div(crop_y, m_block);
    m_rw = floor_div(crop_x + width - 1, m_block) - m_rx0 + 1;
    m_rh = floor_div(crop_y + height - 1, m_block) - m_ry0 + 1;
    m_choice.assign(size_t(std::max(0, m_rw)) * size_t(std::max(0, m_rh)), int8_t(-1));
    m_trials.assign(m_choice.size(), int8_t(1));
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

bool ConnectionAllocation::surface_trials(int x, int y) const {
    const int r = region_of(x, y);
    return !m_fitted || r < 0 || m_trials[size_t(r)] != 0;
}

bool ConnectionAllocation::failed_walk_trials(int x, int y) const {
    const int r = region_of(x, y);
    return m_fitted && r >= 0 && m_trials[size_t(r)] == 2;
}

void ConnectionAllocation::add(int x, int y, const PilotSample& s, double value, double work) {
    const int lx = x - m_crop_x, ly = y - m_crop_y;
    if (m_fitted || lx < 0 || ly < 0 || lx >= m_width || ly >= m_height) return;
    PixelStats& p = m_pixels[size_t(ly) * size_t(m_width) + size_t(lx)];
    bool finite = std::isfinite(value) && std::isfinite(s.m2_pilot);
    for (double m : s.m2) finite = finite && std::isfinite(m);
    for (double m : s.m2_no_trials) finite = finite && std::isfinite(m);
    for (double m : s.m2_failed_walk) finite = finite && std::isfinite(m);
    if (!finite) return;  // the film drops such a sample too
    for (int j = 0; j < kCandidateCount; ++j) {
        p.m2[size_t(j)] += s.m2[size_t(j)];
        p.m2_no_trials[size_t(j)] += s.m2_no_trials[size_t(j)];
        p.m2_failed_walk[size_t(j)] += s.m2_failed_walk[size_t(j)];
    }
    p.m2_pilot += s.m2_pilot;
    p.sum += value;
    p.sum2 += value * value;
    p.work += work;
    p.work_connect += s.work_connect;
    p.work_trials += s.work_trials;
    p.work_density += s.work_density;
    p.work_seed += s.work_seed;
    p.work_probe += s.work_probe;
    p.needs_mnee = p.needs_mnee || s.needs_mnee;
    p.needs_trials = p.needs_trials || s.needs_trials;
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

bool ConnectionAllocation::in_lattice(size_t r) const {
    const size_t k = std::max<size_t>(1, m_choice.size() / kLatticeRegions);
    return r % k == k / 2;
}

std::vector<std::array<int, 4>> ConnectionAllocation::lattice_outside(int x0, int y0, int x1, int y1) const {
    std::vector<std::array<int, 4>> rects;
    if (m_price != WorkPrice::Image) return rects;
    widen_to_regions(x0, y0, x1, y1);
    for (size_t r = 0; r < m_choice.size(); ++r) {
        if (!in_lattice(r)) continue;
        const int rx = int(r % size_t(m_rw)) + m_rx0, ry = int(r / size_t(m_rw)) + m_ry0;
        const int a0 = std::max(0, rx * m_block - m_crop_x), a1 = std::min(m_width, (rx + 1) * m_block - m_crop_x);
        const int b0 = std::max(0, ry * m_block - m_crop_y), b1 = std::min(m_height, (ry + 1) * m_block - m_crop_y);
        // Regions are whole or absent in the widened rectangle.
        if (a0 >= x0 && a1 <= x1 && b0 >= y0 && b1 <= y1) continue;
        rects.push_back({a0, b0, a1, b1});
    }
    return rects;
}

namespace {
constexpr size_t kPilotValues = 3 * kCandidateCount + 12;  // PixelStats as doubles
}  // namespace

std::vector<double> ConnectionAllocation::pilot_state() const {
    std::vector<double> v(m_pixels.size() * kPilotValues, 0.0);
    for (size_t i = 0; i < m_pixels.size(); ++i) {
        const PixelStats& p = m_pixels[i];
        double* d = v.data() + i * kPilotValues;
        for (int j = 0; j < kCandidateCount; ++j) {
            d[j] = p.m2[size_t(j)];
            d[kCandidateCount + j] = p.m2_no_trials[size_t(j)];
            d[2 * kCandidateCount + j] = p.m2_failed_walk[size_t(j)];
        }
        d += 3 * kCandidateCount;
        d[0] = p.m2_pilot;
        d[1] = p.sum;
        d[2] = p.sum2;
        d[3] = p.work;
        d[4] = p.work_connect;
        d[5] = p.work_density;
        d[6] = double(p.n);
        d[7] = p.needs_mnee ? 1.0 : 0.0;
        d[8] = p.work_trials;
        d[9] = p.needs_trials ? 1.0 : 0.0;
        d[10] = p.work_seed;
        d[11] = p.work_probe;
    }
    return v;
}

void ConnectionAllocation::set_pilot_state(const std::vector<double>& v) {
    if (v.size() != m_pixels.size() * kPilotValues) return;
    for (size_t i = 0; i < m_pixels.size(); ++i) {
        PixelStats& p = m_pixels[i];
        const double* d = v.data() + i * kPilotValues;
        for (int j = 0; j < kCandidateCount; ++j) {
            p.m2[size_t(j)] = d[j];
            p.m2_no_trials[size_t(j)] = d[kCandidateCount + j];
            p.m2_failed_walk[size_t(j)] = d[2 * kCandidateCount + j];
        }
        d += 3 * kCandidateCount;
        p.m2_pilot = d[0];
        p.sum = d[1];
        p.sum2 = d[2];
        p.work = d[3];
        p.work_connect = d[4];
        p.work_density = d[5];
        p.n = uint32_t(d[6]);
        p.needs_mnee = d[7] > 0;
        p.work_trials = d[8];
        p.needs_trials = d[9] > 0;
        p.work_seed = d[10];
        p.work_probe = d[11];
    }
}

void ConnectionAllocation::fit() {
    if (m_fitted) return;
    const size_t regions = m_choice.size();
    // Candidates: (with trials, q_j), (without, q_j), then (with trials beside failed straight
    // walks too, q_j); with first, so that a tie keeps them, and the third only where it is
    // strictly better.
    constexpr int kKinds = 3;
    using PerCandidate = std::array<std::array<double, kCandidateCount>, kKinds>;
    std::vector<PerCandidate> variance(regions), work(regions);
    std::vector<bool> needs_mnee(regions, false), needs_trials(regions, false);
    for (auto& v : variance)
        for (auto& a : v) a.fill(0.0);
    for (auto& w : work)
        for (auto& a : w) a.fill(0.0);
    // A pixel far brighter than its region counts as if it were only kOutlierLevel times the
    // region's median pixel mean (its variance scaled by the square of the ratio). Summed
    // absolutely, one pilot firefly (a pixel whose variance dwarfs its region's) made every
    // candidate's variance alike, so the region took the cheapest candidate, 1/64 where light
    // only MNEE produces rules out 0, and its connections, counted 64 times, turned every pixel
    // of it into speckle (the pool's square blocks, issue 26).
    // Every other pixel keeps its absolute weight: dividing each pixel's variance by its own
    // squared mean (relMSE's weighting), from 4 pilot samples, raised relMSE on six of eight
    // gallery cases (docs/experiments.md). The median is the region's own, so a crop chooses as
    // the full film, and the rule does not depend on the light's units.
    std::vector<std::vector<double>> means(regions);
    for (int ly = 0; ly < m_height; ++ly)
        for (int lx = 0; lx < m_width; ++lx) {
            const PixelStats& p = m_pixels[size_t(ly) * size_t(m_width) + size_t(lx)];
            if (p.n > 0 && p.sum > 0) means[size_t(region_of(lx + m_crop_x, ly + m_crop_y))].push_back(p.sum / p.n);
        }
    std::vector<double> level(regions, 0.0);  // above it a pixel is an outlier
    for (size_t r = 0; r < regions; ++r) {
        std::vector<double>& m = means[r];
        if (m.empty()) continue;
        std::nth_element(m.begin(), m.begin() + std::ptrdiff_t(m.size() / 2), m.end());
        level[r] = kOutlierLevel * m[m.size() / 2];
    }
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
            const double work_rest = (p.work - p.work_connect - p.work_density - p.work_probe) / n;
            const double mean = p.sum / n;
            const double weight = mean > level[r] && level[r] > 0 ? sqr(level[r] / mean) : 1.0;
            for (int kind = 0; kind < kKinds; ++kind) {
                const auto& m2 = kind == 0 ? p.m2 : kind == 1 ? p.m2_no_trials : p.m2_failed_walk;
                // The third kind's extra trials are the pilot's probes (made at the pilot's q).
                const double connect =
                    p.work_connect - (kind == 1 ? p.work_trials : 0.0) + (kind == 2 ? p.work_probe : 0.0);
                for (int j = 0; j < kCandidateCount; ++j) {
                    const double q = kConnectCandidates[size_t(j)];
                    variance[r][size_t(kind)][size_t(j)] += weight * (rest + m2[size_t(j)] / n);
                    // A light sample traces its seed with probability q (ManifoldTechnique::connect),
                    // else it makes one shadow ray; work_seed is the seeds' work beyond that ray.
                    work[r][size_t(kind)][size_t(j)] +=
                        work_rest +
                        ((q / m_q_pilot - 1) * p.work_seed + q / m_q_pilot * connect + (q > 0 ? p.work_density : 0.0)) /
                            n;
                }
            }
            needs_mnee[r] = needs_mnee[r] || p.needs_mnee;
            needs_trials[r] = needs_trials[r] || p.needs_trials;
        }
    // The kinds region r may choose: with trials unless told never; without where told so, or
    // where it chooses and the pilot saw no light that only the trials produce. `cost` prices a
    // candidate (kind, j) from its variance (floored: an unbiased estimate may dip below 0) and
    // work; the first of least cost wins, so a tie keeps the trials and the smaller q.
    const bool learned = m_trial_allocation == TrialAllocation::Learned;
    const auto choose = [&](size_t r, auto cost) {
        const std::array<bool, kKinds> allowed = {
            m_trial_allocation != TrialAllocation::Never,
            m_trial_allocation == TrialAllocation::Never || (learned && !needs_trials[r]), m_failed_walk_kind};
        double vmax = 0;
        for (int kind = 0; kind < kKinds; ++kind)
            if (allowed[size_t(kind)])
                for (double v : variance[r][size_t(kind)]) vmax = std::max(vmax, v);
        int best = -1, best_kind = 0;
        double best_cost = 0;
        for (int kind = 0; kind < kKinds; ++kind) {
            if (!allowed[size_t(kind)]) continue;
            for (int j = needs_mnee[r] ? 1 : 0; j < kCandidateCount; ++j) {
                const double v = variance[r][size_t(kind)][size_t(j)];
                const double var = vmax > 0 ? std::max(v, 1e-9 * vmax) : 0.0;
                const double c = cost(v, var, work[r][size_t(kind)][size_t(j)]);
                if (best < 0 || c < best_cost) {
                    best = j;
                    best_kind = kind;
                    best_cost = c;
                }
            }
        }
        const int8_t trials = int8_t(best_kind == 0 ? 1 : best_kind == 1 ? 0 : 2);
        const bool changed = m_choice[r] != best || m_trials[r] != trials;
        m_choice[r] = int8_t(best);
        // q = 0 makes no connection: whether it would run trials does not matter.
        m_trials[r] = trials;
        return changed;
    };
    // Variance x work is a region's inverse efficiency; where the pilot saw no variance at all
    // (a black region) the work alone decides.
    for (size_t r = 0; r < regions; ++r)
        choose(r, [](double, double var, double w) { return (var > 0 ? var : 1.0) * w; });
    if (m_price == WorkPrice::Image) {
        // The image's price of work (docs/mnee.md, "The image's price of work"). Every pixel
        // takes the same samples, so at equal time each region's walks are paid by every pixel:
        // the image's relMSE x time is (sum_r rho_r V_r)(sum_r W_r), with rho_r = 1 / m_r^2 the
        // weight relMSE gives region r (m_r its median pixel mean, floored at kRelativeFloor times
        // the lattice's mean, so that a near-black region's noise does not count without bound).
        // At its minimum every region minimises rho_r V_r + lambda W_r, lambda = sum rho V /
        // sum W: learned by fixed-point rounds on the lattice from the regions' own choices, then
        // one price for every region. A crop, a sample range or an MPI rank learns it from the
        // same lattice, so it chooses as the whole render.
        double msum = 0;
        size_t mcount = 0;
        for (size_t r = 0; r < regions; ++r)
            if (in_lattice(r) && level[r] > 0) {
                msum += level[r] / kOutlierLevel;
                ++mcount;
            }
        const double floor = mcount > 0 ? kRelativeFloor * msum / double(mcount) : 0.0;
        if (floor > 0) {
            std::vector<double> rho(regions);
            for (size_t r = 0; r < regions; ++r) rho[r] = 1.0 / sqr(std::max(level[r] / kOutlierLevel, floor));
            double lambda = 0;
            // Region r's cost of a candidate at the price lambda: rho_r V + lambda W.
            const auto priced = [&](size_t r) {
                return [&, r](double v, double, double w) { return rho[r] * v + lambda * w; };
            };
            for (int round = 0; round < kPriceRounds; ++round) {
                double sv = 0, sw = 0;
                for (size_t r = 0; r < regions; ++r)
                    if (in_lattice(r)) {
                        const size_t kind = m_trials[r] == 1 ? 0 : m_trials[r] == 0 ? 1 : 2, j = size_t(m_choice[r]);
                        sv += rho[r] * variance[r][kind][j];
                        sw += work[r][kind][j];
                    }
                lambda = sw > 0 ? sv / sw : 0.0;
                bool changed = false;
                for (size_t r = 0; r < regions; ++r)
                    if (in_lattice(r)) changed = choose(r, priced(r)) || changed;
                if (!changed) break;
            }
            for (size_t r = 0; r < regions; ++r) choose(r, priced(r));
        }
    }
    m_fitted = true;
    m_pixels = {};
}

uint64_t ConnectionAllocation::regions_with_failed_walk_trials() const {
    uint64_t n = 0;
    for (size_t r = 0; r < m_choice.size(); ++r) n += m_choice[r] > 0 && m_trials[r] == 2;
    return n;
}

uint64_t ConnectionAllocation::regions_without_trials() const {
    uint64_t n = 0;
    for (size_t r = 0; r < m_choice.size(); ++r) n += m_choice[r] > 0 && m_trials[r] == 0;
    return n;
}

std::array<uint64_t, kCandidateCount> ConnectionAllocation::histogram() const {
    std::array<uint64_t, kCandidateCount> h{};
    for (int8_t c : m_choice)
        if (c >= 0) ++h[size_t(c)];
    return h;
}

}  // namespace snell
