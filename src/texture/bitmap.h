#pragma once
// Mitsuba's `bitmap` texture: an image file looked up at uv (after to_uv), v = 0 at the image's
// first (top) row and texel centres at (i + 1/2) / width, as in Mitsuba 3. Filtering is
// `bilinear` (default) or `nearest`; `wrap_mode` repeat (default), mirror or clamp.
//
// Colour handling follows Mitsuba's spectral variants: sRGB-encoded files (8/16-bit PNG, JPEG,
// TIFF) are linearised on load unless `raw`; every RGB texel gets its sigmoid coefficients (Jakob
// & Hanika 2019, from RGBToSpectrumTable) and a lookup interpolates the four texels' *spectra*,
// which is the spectrum of the interpolated colour, since colour is linear in the spectrum.
// Scalar lookups (roughness, weights) read grey files directly and RGB files as luminance.
//
// No MIP-mapping: the integrators carry no ray differentials, and Mitsuba 3's bitmap does not
// filter either (docs/scene-format.md, "Textures").
#include <mutex>
#include <string>
#include <vector>

#include "core/srgb.h"
#include "io/texture_image.h"
#include "texture/texture.h"

namespace snell {

class BitmapTexture final : public Texture {
public:
    enum class Filter { Nearest, Bilinear };
    using Wrap = WrapMode;

    /// `raw`: keep the stored values (no sRGB decoding).
    BitmapTexture(TextureImage image, Filter filter, Wrap wrap, bool raw, Transform to_uv);

    SampledSpectrum eval(const SurfaceInteraction& si, const SampledWavelengths& wl) const override;
    double eval_float(const SurfaceInteraction& si) const override;
    RGB eval_rgb(const SurfaceInteraction& si) const override;
    /// Exact derivative of the bilinear interpolant (Mitsuba's eval_1_grad); 0 for nearest.
    Vec2 eval_float_grad(const SurfaceInteraction& si) const override;
    double mean() const override { return m_mean; }
    double min_value() const override { return m_min; }
    double max_value() const override { return m_max; }

    int width() const { return m_width; }
    std::pair<int, int> resolution() const override { return {m_width, m_height}; }
    int height() const { return m_height; }
    int channels() const { return m_channels; }
    /// Texel index along an axis of n texels after the wrap mode.
    int wrap(int i, int n) const;

private:
    /// The (up to) four texels of a lookup and their weights, in texel indices.
    struct Footprint {
        int x[2], y[2];
        double wx[2], wy[2];
        int count;  ///< 1 (nearest) or 2 per axis (bilinear)
    };
    Footprint footprint(const Vec2& uv) const;
    const float* texel(int x, int y) const { return &m_texels[(size_t(y) * m_width + x) * m_channels]; }
    /// The scalar (grey, or an RGB texel's luminance) of texel (x, y).
    double texel_float(int x, int y) const {
        const float* t = texel(x, y);
        return m_channels == 1 ? t[0] : RGB(t[0], t[1], t[2]).luminance();
    }
    /// Sigmoid coefficients per RGB texel, computed on the first spectral lookup.
    const std::vector<float>& coefficients() const;

    int m_width, m_height, m_channels;
    std::vector<float> m_texels;  ///< linear values (or raw), row-major from the top row
    Filter m_filter;
    Wrap m_wrap;
    Transform m_to_uv;
    double m_mean = 0, m_min = 0, m_max = 0;
    mutable std::once_flag m_coeff_once;
    mutable std::vector<float> m_coeffs;
};

}  // namespace snell
