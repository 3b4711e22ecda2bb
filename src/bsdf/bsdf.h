#pragma once
// BSDF interface. Conventions (as in pbrt/Mitsuba):
//  - directions are in the local shading frame (n = +z), both point *away* from the surface:
//    wo towards the previous path vertex (camera side), wi towards the next (light side);
//  - eval returns f_r(wo, wi) without the cosine factor;
//  - pdf is in solid angle of wi; deltas have eval = pdf = 0 and are only sampled;
//  - values are SampledSpectrum at the path's wavelengths ctx.wl; directions, pdfs and lobe
//    choices belong to the hero wavelength ctx.wl.hero() (Wilkie et al. 2014).
#include <cstdint>
#include <optional>

#include "bsdf/microfacet.h"
#include "core/object.h"
#include "core/spectrum.h"
#include "core/vector.h"
#include "geometry/interaction.h"

namespace snell {

enum class TransportMode { Radiance, Importance };

/// Lobe classification flags (bitwise).
enum BSDFFlags : uint32_t {
    kReflection = 1u << 0,
    kTransmission = 1u << 1,
    kDiffuse = 1u << 2,
    kGlossy = 1u << 3,
    kSpecular = 1u << 4,
};

struct BSDFContext {
    SampledWavelengths wl = SampledWavelengths::single(550.0);  ///< the path's wavelengths (nm)
    TransportMode mode = TransportMode::Radiance;
    /// The surface point the BSDF is evaluated at: its textures are read there (a material gives
    /// the BSDF at the hit, as in pbrt-v4). Set per vertex with at(); the manifold walk sets it
    /// to every projected vertex, so a texture is read where the converged vertex lies.
    const SurfaceInteraction* si = nullptr;

    double hero() const { return wl.hero(); }
    BSDFContext at(const SurfaceInteraction& p) const {
        BSDFContext c = *this;
        c.si = &p;
        return c;
    }
    /// The point for texture lookups. A textured BSDF evaluated without one is a bug of the
    /// caller: counted (bsdf.lookups_without_point, which the tests require to stay 0), and read
    /// at uv = (0, 0).
    const SurfaceInteraction& point() const;
};

struct BSDFSample {
    Vec3 wi;                 ///< sampled direction (local)
    SampledSpectrum weight;  ///< f * |cos theta_i| / pdf per wavelength (for deltas: the discrete weight)
    double pdf = 0;          ///< solid angle density; for deltas the discrete lobe probability
    double eta = 1;          ///< relative IOR across the sampled transmission (1 for reflection)
    uint32_t lobe = 0;       ///< BSDFFlags of the sampled lobe
    /// The direction exists for the hero wavelength only (refraction through a dispersive
    /// interface): `weight` holds the hero's value, the integrator drops the others
    /// (SampledWavelengths::hero_only) once per path.
    bool hero_only = false;
    bool is_delta() const { return (lobe & kSpecular) != 0; }
};

class BSDF : public Object {
public:
    virtual SampledSpectrum eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const = 0;
    /// Solid-angle density of sample() at the hero wavelength.
    virtual double pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const = 0;
    /// `uc` picks a lobe, `u` samples it.
    virtual std::optional<BSDFSample> sample(const BSDFContext& ctx, const Vec3& wo, double uc,
                                             const Vec2& u) const = 0;
    /// Union of the lobes' flags.
    virtual uint32_t flags() const = 0;

    bool has_delta() const { return (flags() & kSpecular) != 0; }
    bool is_transmissive() const { return (flags() & kTransmission) != 0; }
    /// Non-delta lobes exist (light sampling is worthwhile).
    bool is_smooth_sampled() const { return (flags() & (kDiffuse | kGlossy)) != 0; }
    /// A refractive interface at `lambda`: transmissive, smooth or microfacet, eta != 1 (the
    /// surfaces a manifold chain lies on, and the casters of caster sampling).
    bool is_refractive_interface(double lambda) const {
        return is_transmissive() && (has_delta() || has_microfacet()) && eta(lambda) != 1.0;
    }

    /// Paper Eq. 9: the value kappa of a delta lobe in delta-half-vector measure for a pair
    /// (wo, wi) that obeys the specular law -- Fresnel R for reflection, (1 - F) with the
    /// radiance scaling for refraction, times the specular factors. 0 without delta lobes.
    /// Evaluated per wavelength for the given (hero) geometry.
    virtual SampledSpectrum eval_delta(const BSDFContext& /*ctx*/, const Vec3& /*wo*/, const Vec3& /*wi*/) const {
        return {};
    }
    /// Discrete probability with which sample() picks the delta lobe connecting wo to wi (hero).
    virtual double pdf_delta(const BSDFContext& /*ctx*/, const Vec3& /*wo*/, const Vec3& /*wi*/) const { return 0; }
    /// A rough interface with a microfacet distribution (MNEE samples its half vectors from it,
    /// paper Sec. 3.2).
    virtual bool has_microfacet() const { return false; }
    /// That distribution at ctx's point (a roughness texture is read there), or none.
    virtual std::optional<MicrofacetDistribution> microfacet(const BSDFContext& /*ctx*/) const { return std::nullopt; }

    /// Interior over exterior IOR at lambda (1 for non-dielectrics). Used by MNEE's constraints.
    virtual double eta(double /*lambda*/) const { return 1.0; }
    /// eta depends on the wavelength (Abbe number > 0): refracted directions are the hero's.
    virtual bool dispersive() const { return false; }
    /// Whether evaluating it reads the surface point's uv (a textured parameter). Default true;
    /// BSDFs whose parameters are all constant say false, and a shape whose BSDF and emitter
    /// read no uv is spared computing it (Shape::reads_uv).
    virtual bool reads_uv() const { return true; }
    /// Beer-Lambert absorption coefficient of the enclosed medium (1/scene unit), or nullptr.
    virtual const Spectrum* interior_absorption() const { return nullptr; }
};

}  // namespace snell
