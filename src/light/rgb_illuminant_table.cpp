#include "light/rgb_illuminant_table.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace snell {

namespace {
constexpr int kSide = RGBIlluminantTable::kN + 1;

// RGB of lattice node (face, ia, ib): component `face` is 1, the next two (cyclically) are
// ia/N and ib/N.
RGB node_rgb(int face, int ia, int ib) {
    double c[3];
    c[face] = 1.0;
    c[(face + 1) % 3] = double(ia) / RGBIlluminantTable::kN;
    c[(face + 2) % 3] = double(ib) / RGBIlluminantTable::kN;
    return {c[0], c[1], c[2]};
}
}  // namespace

RGBIlluminantTable::RGBIlluminantTable() : m_nodes(size_t(3 * kSide * kSide)) {
    // Fits are independent; Spectrum's own cache makes shared edge nodes cheap.
    tbb::parallel_for(0, 3 * kSide * kSide, [&](int i) {
        const int face = i / (kSide * kSide), ia = (i / kSide) % kSide, ib = i % kSide;
        m_nodes[size_t(i)] = Spectrum::from_rgb_illuminant(node_rgb(face, ia, ib));
    });
}

const RGBIlluminantTable& RGBIlluminantTable::get() {
    static const RGBIlluminantTable table;
    return table;
}

namespace {
// The bilinear blend of lattice spectra, for one wavelength (double) or a path's (SampledWavelengths).
template <class Wavelengths, class Value>
Value blend(const std::vector<Spectrum>& nodes, int side, int n, const RGB& rgb_in, const Wavelengths& lambda) {
    const double c[3] = {std::max(0.0, rgb_in.r), std::max(0.0, rgb_in.g), std::max(0.0, rgb_in.b)};
    const int face = c[0] >= c[1] ? (c[0] >= c[2] ? 0 : 2) : (c[1] >= c[2] ? 1 : 2);
    const double m = c[face];
    if (!(m > 0)) return Value(0.0);
    // Face coordinates in [0, 1] and their lattice cell.
    const double a = c[(face + 1) % 3] / m * n, b = c[(face + 2) % 3] / m * n;
    const int ia = std::min(n - 1, int(a)), ib = std::min(n - 1, int(b));
    const double fa = a - ia, fb = b - ib;
    const Spectrum* base = &nodes[size_t(face * side * side + ia * side + ib)];
    Value s(0.0);
    // Skip zero weights: grey and lattice-aligned colours evaluate a single node exactly.
    if (fa < 1 && fb < 1) s += (1 - fa) * (1 - fb) * base[0].eval(lambda);
    if (fa < 1 && fb > 0) s += (1 - fa) * fb * base[1].eval(lambda);
    if (fa > 0 && fb < 1) s += fa * (1 - fb) * base[side].eval(lambda);
    if (fa > 0 && fb > 0) s += fa * fb * base[side + 1].eval(lambda);
    return m * s;
}
}  // namespace

double RGBIlluminantTable::eval(const RGB& rgb, double lambda) const {
    return blend<double, double>(m_nodes, kSide, kN, rgb, lambda);
}

SampledSpectrum RGBIlluminantTable::eval(const RGB& rgb, const SampledWavelengths& wl) const {
    return blend<SampledWavelengths, SampledSpectrum>(m_nodes, kSide, kN, rgb, wl);
}

}  // namespace snell
