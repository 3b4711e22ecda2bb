#include "light/texture_emission.h"

#include <algorithm>

#include "core/rgb_to_spectrum_table.h"

namespace snell {

SampledSpectrum texture_emission(const Texture& t, const SurfaceInteraction& si, const SampledWavelengths& wl) {
    const RGB rgb = t.eval_rgb(si);
    const double m = rgb.max();
    if (!(m > 0)) return SampledSpectrum(0.0);
    const std::array<double, 3> c = RGBToSpectrumTable::reflectance()(RGB(rgb.r / m, rgb.g / m, rgb.b / m));
    SampledSpectrum out;
    for (int k = 0; k < kSpectrumSamples; ++k) out[k] = m * sigmoid_polynomial(c, wl[k]);
    return out;
}

}  // namespace snell
