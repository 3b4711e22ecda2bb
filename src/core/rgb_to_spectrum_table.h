#pragma once
// Spectral upsampling of texels (Jakob & Hanika 2019, Sec. 4; pbrt-v4's RGBToSpectrumTable): a
// reflectance RGB becomes the coefficients of a sigmoid polynomial by trilinear interpolation in
// a precomputed table instead of a per-colour fit. Constant colours keep the exact fit of
// Spectrum::from_rgb_reflectance; textures, with a colour per texel, need this.
#include <array>
#include <vector>

#include "core/spectrum.h"

namespace snell {

class RGBToSpectrumTable {
public:
    /// Grid points per axis. The table is (max component) x (z) x (y) x (x) of 3 coefficients.
    static constexpr int kRes = 32;

    /// The table for reflectances under the renderer's white; built on first use (about a
    /// second on two cores: warm-started fits, see the .cpp), then shared by every texture.
    static const RGBToSpectrumTable& reflectance();

    /// Coefficients for sigmoid_polynomial() whose spectrum reproduces `rgb` (clamped to [0, 1]).
    /// Greys are exact (c0 = c1 = 0).
    std::array<double, 3> operator()(const RGB& rgb) const;

private:
    RGBToSpectrumTable();
    float* at(int maxc, int zi, int yi, int xi) {
        return &m_coeffs[(((size_t(maxc) * kRes + zi) * kRes + yi) * kRes + xi) * 3];
    }
    const float* at(int maxc, int zi, int yi, int xi) const {
        return &m_coeffs[(((size_t(maxc) * kRes + zi) * kRes + yi) * kRes + xi) * 3];
    }

    std::array<double, kRes> m_z{};  ///< grid of the largest component: denser near 0 and 1
    std::vector<float> m_coeffs;
};

}  // namespace snell
