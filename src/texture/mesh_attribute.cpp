#include "texture/mesh_attribute.h"

#include <algorithm>

#include "core/rgb_to_spectrum_table.h"
#include "geometry/shape.h"

namespace snell {

int MeshAttributeTexture::lookup(const SurfaceInteraction& si, double v[3]) const {
    const int c = si.shape ? si.shape->attribute(m_name, si, v) : 0;
    for (int k = 0; k < c; ++k) v[k] *= m_scale;
    return c;
}

SampledSpectrum MeshAttributeTexture::eval(const SurfaceInteraction& si, const SampledWavelengths& wl) const {
    double v[3] = {};
    const int c = lookup(si, v);
    if (c == 1) return SampledSpectrum(v[0]);
    if (c != 3) return SampledSpectrum(0.0);
    // A colour as a reflectance spectrum (Mitsuba 3 turns colour attributes into its sRGB
    // model's coefficients); the scale rides on top, as bitmap's does.
    const double m = std::max({v[0], v[1], v[2]});
    if (!(m > 0)) return SampledSpectrum(0.0);
    const double s = m > 1 ? m : 1.0;
    const std::array<double, 3> coeff = RGBToSpectrumTable::reflectance()(RGB(v[0] / s, v[1] / s, v[2] / s));
    SampledSpectrum out;
    for (int k = 0; k < kSpectrumSamples; ++k) out[k] = s * sigmoid_polynomial(coeff, wl[k]);
    return out;
}

double MeshAttributeTexture::eval_float(const SurfaceInteraction& si) const {
    double v[3] = {};
    const int c = lookup(si, v);
    if (c == 1) return v[0];
    return c == 3 ? RGB(v[0], v[1], v[2]).luminance() : 0.0;
}

RGB MeshAttributeTexture::eval_rgb(const SurfaceInteraction& si) const {
    double v[3] = {};
    const int c = lookup(si, v);
    if (c == 1) return RGB(v[0]);
    return c == 3 ? RGB(v[0], v[1], v[2]) : RGB(0.0);
}

}  // namespace snell
