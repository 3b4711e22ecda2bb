#pragma once
// Which technique of the path-tracing family produced each part of a sample's radiance, and the
// per-sample statistics of each (issue 10: "each technique's mean and relative variance of
// contributions"). A few fireflies of one technique dominate an image's error; these moments
// say which technique they come from before anyone tunes anything.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/sampled_spectrum.h"

namespace snell {

enum class Technique : uint8_t {
    Emitted,        ///< an emitter seen directly by the camera (or escaped to the environment)
    BsdfHit,        ///< an emitter reached by BSDF sampling after a non-refractive vertex
    BsdfRefracted,  ///< an emitter reached by BSDF sampling through refractive interfaces after x_b
    BsdfReflected,  ///< the same with an internal reflection among those interfaces (not MNEE's class)
    Nee,            ///< next event estimation (a shadow ray)
    MneeStraight,   ///< MNEE: the solution walked from the straight seed (paper Alg. 1)
    MneeSurface,    ///< MNEE: solutions walked from seeds sampled on the caster shapes (SMS)
    MneeReflected,  ///< MNEE's reflected connection: light reflected once off the outside of glass
};
inline constexpr int kTechniqueCount = 8;
static_assert(kTechniqueCount < 128, "the film keeps a pixel's technique in an int8_t");

/// The short names used in the statistics ("path.technique.<name>").
const char* technique_name(Technique t);
/// All of them in Technique's order (SampleTracer::technique_names).
std::vector<std::string> path_technique_names();

/// One camera sample's radiance per technique; converted to luminance once, when recorded.
class TechniqueLog {
public:
    void add(Technique t, const SampledSpectrum& v) { m_by[size_t(t)] += v; }
    /// Adds this sample's luminance (CIE Y, divided by the wavelengths' density) of every
    /// technique (zeros included) to the render's statistics ("path.technique.<name>",
    /// StatMoments), and their sum to "path.sample"; notes the technique with the largest
    /// part for the film's dominance statistics (SampleEstimate::technique).
    int record(const SampledWavelengths& wl) const;

private:
    std::array<SampledSpectrum, kTechniqueCount> m_by{};
};

}  // namespace snell
