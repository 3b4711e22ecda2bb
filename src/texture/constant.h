#pragma once
// A parameter given as <float>, <rgb> or <spectrum>: the same value at every point.
#include "texture/texture.h"

namespace snell {

class ConstantTexture final : public Texture {
public:
    /// `spectrum` for colour lookups, `scalar` for eval_float (a float parameter's value, or a
    /// colour's luminance), `rgb` for eval_rgb (the <rgb> as given, e.g. a normal map's colour).
    ConstantTexture(Spectrum spectrum, double scalar, RGB rgb)
        : m_spectrum(std::move(spectrum)), m_scalar(scalar), m_rgb(rgb) {}
    static TextureRef make(Spectrum s, double scalar, RGB rgb) {
        return std::make_shared<ConstantTexture>(std::move(s), scalar, rgb);
    }
    static TextureRef make(Spectrum s, double scalar) { return make(std::move(s), scalar, RGB(scalar)); }
    static TextureRef make(double v) { return make(Spectrum::constant(v), v); }

    SampledSpectrum eval(const SurfaceInteraction&, const SampledWavelengths& wl) const override {
        return m_spectrum.eval(wl);
    }
    double eval_float(const SurfaceInteraction&) const override { return m_scalar; }
    RGB eval_rgb(const SurfaceInteraction&) const override { return m_rgb; }
    double mean() const override { return m_scalar; }
    double min_value() const override { return m_scalar; }
    double max_value() const override { return m_scalar; }
    bool is_constant() const override { return true; }

    const Spectrum& spectrum() const { return m_spectrum; }

private:
    Spectrum m_spectrum;
    double m_scalar;
    RGB m_rgb;
};

}  // namespace snell
