#pragma once
// Fast RGB -> emission spectrum upsampling for textured emitters (environment maps).
#include <vector>

#include "core/spectrum.h"

namespace snell {

/// Evaluates Spectrum::from_rgb_illuminant-like spectra for arbitrary non-negative RGB without
/// a per-colour fit. An RGB is split into its maximum m and chromaticity c = rgb / m, which
/// lies on one of the three cube faces where a component equals 1. Each face carries an
/// (N+1)^2 lattice of fitted spectra S_node = from_rgb_illuminant(node), and
///     S(rgb)(lambda) = m * sum_corners w_corner * S_corner(lambda)
/// with bilinear weights in the face coordinates. Because projecting a spectrum to RGB is
/// linear and bilinear weights reproduce c exactly, S(rgb) maps back to rgb (up to the fit
/// residual of the nodes); the result is smooth and non-negative, continuous across faces
/// (edge nodes coincide), and grey rgb (v,v,v) gives exactly v times the white illuminant.
/// Interpolating fitted spectra rather than fitting each texel keeps loading fast: at most
/// 3 (N+1)^2 fits, done once per process.
class RGBIlluminantTable {
public:
    static constexpr int kN = 8;  ///< lattice cells per face axis

    /// The process-wide table (built on first use, thread-safe).
    static const RGBIlluminantTable& get();

    /// Spectral radiance at `lambda` (nm) of emission colour `rgb` (negative parts clamped).
    double eval(const RGB& rgb, double lambda) const;
    /// The same at every wavelength a path carries.
    SampledSpectrum eval(const RGB& rgb, const SampledWavelengths& wl) const;

private:
    RGBIlluminantTable();
    std::vector<Spectrum> m_nodes;  // 3 faces x (kN+1) x (kN+1)
};

}  // namespace snell
