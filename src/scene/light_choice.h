#pragma once
// The light sample of next event estimation, shared by every technique that connects to lights
// (NEE in integrators/light_connection.h, MNEE's Alg. 1 line 1 in manifold/manifold_technique.h):
// a light from the scene's light sampler, then a point on it as seen from the shading point.
#include <optional>

#include "core/sampled_spectrum.h"
#include "light/light.h"

namespace snell {

class Scene;
class Sampler;
struct SurfaceInteraction;

/// Picks a light (the scene's light sampler) and samples a point on it as seen from `si`; the
/// chosen light and its probability go to `light` and `pmf`. `keep_dark` keeps samples that
/// emit nothing towards si (a spot light seen from outside its cone): MNEE reaches the light
/// along another direction. Draws next_1d() then next_2d(), whatever happens.
std::optional<LightSample> sample_light(const Scene& scene, const SurfaceInteraction& si, const SampledWavelengths& wl,
                                        Sampler& sampler, const Light** light, double* pmf, bool keep_dark = false);

/// Whether the light sample `ls` is in plain sight of `si`: its shadow ray (to the point, or
/// along the direction for lights at infinity) meets nothing.
bool light_visible(const Scene& scene, const SurfaceInteraction& si, const LightSample& ls);

}  // namespace snell
