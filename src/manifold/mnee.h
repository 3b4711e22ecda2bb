#pragma once
// Manifold next event estimation (Hanika, Droske & Fascione 2015): sampling a light connection
// through refractive interfaces (Alg. 1) and evaluating its density for MIS (Alg. 2), with the
// measurement in half-vector space (Eq. 6, Eq. 9). Independent of any integrator.
//
// Measures. The chain x_1..x_k and the light point x_c are measured in vertex area; the
// density of a specular vertex is written without its Dirac delta in half-vector space, and
// every competing technique (BSDF sampling, NEE from the last rough vertex) is expressed with
// the same deltas factored out (Sec. 3.3, "Specular Case"), so MIS compares like with like.
#include <vector>

#include "bsdf/bsdf.h"
#include "core/medium_stack.h"
#include "core/sampler.h"
#include "geometry/interaction.h"
#include "light/light.h"
#include "manifold/half_vectors.h"
#include "manifold/light_point.h"
#include "manifold/manifold_vertex.h"
#include "manifold/mnee_settings.h"
#include "manifold/seed_path.h"

namespace snell {

class Scene;

/// Outcome of one MNEE connection attempt.
enum class MneeOutcome {
    Success,
    NoLightSample,
    SeedOccluded,
    SeedTooMany,
    SeedCulled,
    NoConvergence,
    Stalled,
    Singular,
    ProjectionFailed,
    WrongScattering,
    Occluded,
    Zero,  ///< admissible and visible, but the measurement vanished (e.g. back of the light)
};

/// A connection from x_b to a light through a refractive chain.
struct MneeConnection {
    MneeOutcome outcome = MneeOutcome::Zero;
    SampledSpectrum value;  ///< f(X) / p(X) of Alg. 1 (light pmf included), before MIS
    /// The chain disperses: the path was solved for the hero wavelength and `value` holds
    /// the hero's alone (see SampledWavelengths::hero_only).
    bool hero_only = false;
    double pdf_mnee = 0;      ///< area density of this technique (Eq. 7 with Eq. 8)
    double pdf_bsdf = 0;      ///< area density of BSDF sampling x_1..x_k, x_c from x_b
    double pdf_nee_last = 0;  ///< area density of NEE from x_k (0 unless x_k is rough)
    /// BSDF sampling's solid-angle density of x_b's direction towards x_1 (BSDF::pdf), the first
    /// factor of pdf_bsdf and pdf_nee_last: a path tracer that samples that direction otherwise
    /// (caster sampling) puts its own density in its place.
    double pdf_xb_direction = 0;
    /// Focusing ratio r = |do_b/dx_c| |x_c - x_b|^2 / |cos theta_c| (1 through free space;
    /// MneeSettings::max_geometry clamps it). `value` is already clamped.
    double focusing = 0;
    /// The manifold walk converged (to an admissible path or not, visible or not): Alg. 2's
    /// walk from the same seed and half vectors converges too (surface_weight's domain).
    bool walk_converged = false;
};

/// |do/dh|: solid angle of the light-side direction wo per solid angle of the half vector at
/// vertex v, with the camera-side direction wi fixed (Walter et al. 2007, Eqs. 14 and 16).
double half_vector_jacobian(const ManifoldVertex& v, const Vec3& wi, const Vec3& wo, const Vec3& h);

/// The scattering factor of vertex v in half-vector measure (Eq. 6's factor of f_dH): kappa
/// (Eq. 9) if specular, else f_r |cos o| |do/dh| / |cos h|. Alg. 1 divides the product by
/// p_dH(H) (half_vector_density) in its last line.
SampledSpectrum vertex_measurement(const ManifoldVertex& v, const Vec3& wi, const Vec3& wo, const BSDFContext& ctx);

/// Density with which BSDF sampling at v produces wo from wi: solid angle for rough
/// vertices, lobe probability / |do/dh| for specular ones (delta factored out in h).
double vertex_bsdf_density(const ManifoldVertex& v, const Vec3& wi, const Vec3& wo, const BSDFContext& ctx);

/// p_dH of a vertex's half vector: D(h) (projected solid angle) for rough, 1 for specular.
double half_vector_density(const ManifoldVertex& v, const Vec3& h);

/// Alg. 1 for a light point `lp` (from NEE's light sample, light pmf `pmf`) whose seed segment
/// from x_b crossed the refractive vertices in `chain` (consumed). `media` is the medium at x_b.
MneeConnection mnee_connect(const Scene& scene, const MneeSettings& settings, const SurfaceInteraction& xb,
                            const BSDF& bsdf_b, const BSDFContext& ctx, const MediumStack& media, const Light& light,
                            double pmf, const LightPoint& lp, std::vector<ManifoldVertex>& chain, Sampler& sampler);

/// Alg. 1 with the half vectors of `draws` (the same targets for every walk of one light
/// connection, whatever its seed).
MneeConnection mnee_connect(const Scene& scene, const MneeSettings& settings, const SurfaceInteraction& xb,
                            const BSDF& bsdf_b, const BSDFContext& ctx, const MediumStack& media, const Light& light,
                            double pmf, const LightPoint& lp, std::vector<ManifoldVertex>& chain,
                            HalfVectorDraws& draws);

/// Alg. 1 lines 3-4 alone: culling, half vectors, the walk and admissibility, without
/// visibility or measurement. Success for an admissible chain. `trial_only`: the caller asks only
/// which solution the seed walks to (a Bernoulli trial of solutions=unbiased); an admissible
/// chain then ends its walk as found.
MneeOutcome mnee_walk(const Scene& scene, const MneeSettings& settings, const SurfaceInteraction& xb,
                      const BSDF& bsdf_b, const LightPoint& lp, std::vector<ManifoldVertex>& chain,
                      HalfVectorDraws& draws, bool trial_only = false);

/// Tangent basis at the light point: the light's tangent plane (area measure), or for lights
/// without area (point, spot) the plane perpendicular to the arriving direction.
TangentBasis light_point_basis(const Vec3& p, const Vec3& n, const Vec3& arrival_dir);

/// The straight seed x_b -> x_c (Alg. 2, line 2), traced once when several densities of the same
/// path need it.
struct StraightSeed {
    SeedStatus status = SeedStatus::Clear;
    std::vector<ManifoldVertex> chain;
};
StraightSeed trace_straight_seed(const Scene& scene, const SurfaceInteraction& xb, const Vec3& xc, double lambda,
                                 const MneeSettings& settings);

/// Alg. 2 lines 1, 3 and 8 (light point, the path's own half vectors, |dH/dX|) for the path x_b,
/// chain[0..k), x_c, without the seed's trace or its walk: the density any MNEE estimator gives
/// the path where it produces it at all (surface_weight only lowers it), so an upper bound on
/// every estimator's density() that costs no ray. The MIS cutoff (mis_cutoff) reads it.
double solution_density_bound(const Scene& scene, const MneeSettings& settings, const SurfaceInteraction& xb,
                              const BSDF& bsdf_b, const SurfaceInteraction* chain, int k, const Light& light,
                              double pmf, const Vec3& xc, const Vec3& nc, double lambda);

/// The density of the all-solutions technique for the path x_b, chain[0..k), x_c: Alg. 2 lines
/// 1, 3 and 8 (light point, half vectors, |dH/dX|) without its walk, times the indicator of the
/// technique's domain (a refractive interface lies on the straight segment from x_b to x_c,
/// whether an opaque surface blocks it or not, and the seed is not culled): solution_density_bound
/// where that domain holds. Every solution there is the technique's, found or not.
double solution_density(const Scene& scene, const MneeSettings& settings, const SurfaceInteraction& xb,
                        const BSDF& bsdf_b, const SurfaceInteraction* chain, int k, const Light& light, double pmf,
                        const Vec3& xc, const Vec3& nc, double lambda, const StraightSeed* traced = nullptr);

/// Alg. 2: area density with which MNEE from x_b produces the path x_b, chain[0..k), x_c, at
/// the hero wavelength `lambda`.
/// 0 if the seed path from x_b to x_c walks to a different path (or none). `traced`: the straight
/// seed when the caller has it already (else traced here). `walk_converged`: whether the walk
/// ran (the seed crosses the path's shapes in its order) and converged, to this path or another.
double mnee_pdf(const Scene& scene, const MneeSettings& settings, const SurfaceInteraction& xb, const BSDF& bsdf_b,
                const SurfaceInteraction* chain, int k, const Light& light, double pmf, const Vec3& xc, const Vec3& nc,
                double lambda, const StraightSeed* traced = nullptr, bool* walk_converged = nullptr);

/// The path x_b, path[0..k), x_c as a manifold chain at wavelength `lambda`, each vertex's target
/// its own half vector (Alg. 2, line 3) and scattering as the path scatters there, with the
/// unit-roughness slope of each slot (the draw that gives that target; (0, 0) where specular):
/// the keyed estimator walks its replayed trials with them. False where a vertex is not a
/// manifold interface.
bool chain_of_path(const SurfaceInteraction& xb, const SurfaceInteraction* path, int k, const Vec3& xc, double lambda,
                   std::vector<ManifoldVertex>* chain, std::vector<Vec2>* unit_slopes);

/// A converged chain between x_b and x_c scatters as it asks: each vertex reflects or refracts
/// as its `reflect` says, and both directions see the (micro)facet from their own side.
bool chain_admissible(const Vec3& xb, const std::vector<ManifoldVertex>& chain, const Vec3& xc);

/// Culling of a seed at x_b with the tolerance margin of Fig. 3.
bool mnee_seed_culled(const SurfaceInteraction& xb, const BSDF& bsdf_b, const Vec3& xc, double margin);

}  // namespace snell
