#pragma once
// Textures read by emitters (area radiance, projector irradiance, a spot light's pattern).
// Texture::eval upsamples a texel as a reflectance, bounded to [0, 1] (issue 30: an area light
// with a radiance texture of 1, 2, 10 or 100 rendered the same image). Emission is unbounded: a
// texel keeps its own reflectance-like spectrum, as Mitsuba 3 gives a texture in an emitter (not
// a D65-based one as for an <rgb>; tests/stat/test_mitsuba_references.cpp's textured projector),
// scaled by its largest component.
#include "core/sampled_spectrum.h"
#include "geometry/interaction.h"
#include "texture/texture.h"

namespace snell {

/// The texture's linear RGB at si as unbounded emission: its largest component m times the
/// reflectance spectrum of rgb / m (so the spectrum scales with the texel, and a grey (v, v, v)
/// is exactly v at every wavelength).
SampledSpectrum texture_emission(const Texture& t, const SurfaceInteraction& si, const SampledWavelengths& wl);

}  // namespace snell
