#pragma once
// Tracks which absorbing dielectric interior a path is travelling through, so Beer-Lambert
// attenuation exp(-sigma_a t) can be applied per segment (coloured glass, tinted water).
// Dielectrics are closed surfaces with outward normals: transmission entering through the
// front side pushes the interior, leaving through the back side pops it.
#include <array>
#include <cmath>

#include "core/spectrum.h"

namespace snell {

class MediumStack {
public:
    /// Transmission through a surface whose BSDF has interior absorption `sigma_a` (may be
    /// nullptr for a clear dielectric); `entering` is true when the path crosses from the
    /// outside (normal side) to the inside.
    void cross(const Spectrum* sigma_a, bool entering) {
        if (entering) {
            if (m_size < kMax) m_stack[m_size] = sigma_a;
            ++m_size;
        } else if (m_size > 0) {
            --m_size;
        }
    }
    /// Transmittance of a segment of length t inside the current medium, per wavelength.
    SampledSpectrum transmittance(double t, const SampledWavelengths& wl) const {
        if (m_size == 0 || m_size > kMax) return SampledSpectrum(1.0);
        const Spectrum* s = m_stack[m_size - 1];
        if (!s) return SampledSpectrum(1.0);
        return exp(s->eval(wl) * -t);
    }
    bool inside() const { return m_size > 0; }

private:
    static constexpr int kMax = 8;
    std::array<const Spectrum*, kMax> m_stack{};
    int m_size = 0;
};

}  // namespace snell
