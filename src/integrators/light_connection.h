#pragma once
// Next event estimation pieces shared by the integrators that connect to lights (nee, mnee,
// and through them pssmlt and erpt): the light choice, the connection with its shadow ray,
// and its power-heuristic weight against BSDF sampling.
#include <optional>

#include "core/medium_stack.h"
#include "core/sampled_spectrum.h"
#include "scene/light_choice.h"

namespace snell {

class Scene;
class Sampler;
class BSDF;
class CasterSampling;
class Light;
struct BSDFContext;
struct LightSample;
struct SurfaceInteraction;

/// NEE for an already drawn light sample: shadow ray, power heuristic against BSDF sampling.
/// `media` is the medium the path is in at si. `light_share`, `bsdf_share`: the two techniques'
/// shares of the samples when they take several each (Veach's n_i in n_i p_i; Mitsuba's direct).
SampledSpectrum nee_connect(const Scene& scene, const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& ctx,
                            const MediumStack& media, const LightSample& ls, double pmf, double light_share = 1,
                            double bsdf_share = 1);

/// The same for the path-tracing family, whose walk samples directions with `directions`
/// (BSDF sampling mixed with caster sampling): its density is the one NEE is weighed against.
SampledSpectrum nee_connect(const Scene& scene, const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& ctx,
                            const MediumStack& media, const LightSample& ls, double pmf,
                            const CasterSampling& directions);

/// MIS weight of NEE against BSDF sampling (power heuristic, solid angle, with the sample
/// shares as for nee_connect); 1 for delta lights. With `directions`, BSDF sampling's density
/// is theirs (CasterSampling::pdf).
double nee_weight(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& ctx, const LightSample& ls,
                  double pmf, double light_share = 1, double bsdf_share = 1,
                  const CasterSampling* directions = nullptr);

/// NEE estimate for a visible light sample with BSDF value `f` (towards ls.wi) and MIS weight
/// `w`: f |cos| Tr Le w / (pmf pdf).
SampledSpectrum nee_estimate(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& ctx,
                             const MediumStack& media, const LightSample& ls, const SampledSpectrum& f, double pmf,
                             double w);

}  // namespace snell
