#pragma once
// The manifold light-connection technique (paper Alg. 1 and Alg. 2) behind one interface: from
// a light sample at x_b and its seed path, the admissible paths found (a SolutionSet, each with
// its value and the densities MIS needs), and the density with which the technique produces a
// given path. It runs the estimator the settings name (straight_seed_estimator.h: the paper's;
// all_solutions_estimator.h, unbiased_estimator.h, fallback_estimator.h,
// keyed_trials_estimator.h), once per wavelength
// through dispersive chains. The `mnee` integrator composes with it; it knows nothing of
// integrators.
#include <vector>

#include "core/medium_stack.h"
#include "core/rng.h"
#include "core/sampler.h"
#include "manifold/light_point.h"
#include "manifold/mnee.h"
#include "manifold/mnee_settings.h"
#include "manifold/solution_set.h"
#include "scene/light_choice.h"

namespace snell {

class CasterSampling;
class Scene;
class Shape;

/// The path at x_b as the technique needs it.
struct ManifoldQuery {
    const SurfaceInteraction* xb = nullptr;
    const BSDF* bsdf_b = nullptr;
    BSDFContext ctx;
    MediumStack media;       ///< the medium at x_b
    bool hero_only = false;  ///< the path's throughput already carries the hero wavelength alone
    /// The straight seed may be walked (false: an opaque surface blocks the segment x_b -> x_c,
    /// SeedStatus::Blocked; only surface seeds are tried). connect() sets it.
    bool straight_seed = true;
    /// connect(): q, the probability with which a connection to a light that BSDF sampling can
    /// hit is made (ConnectionAllocation; 0: not at all, its light is left to BSDF sampling).
    /// Delta lights are always connected.
    double connect_probability = 1;
    /// Set by connect() outside the pilot (`meter_work` false): the q the caller weighs the
    /// solutions with. The 1 / p estimate then skips a solution mis_cutoff gives no MIS weight,
    /// and the solution counts 0. 0: every solution counted (the pilot's record reads the counts).
    double cutoff_q = 0;
    /// The longest chain max_depth allows here (-1: any).
    int max_k = -1;
    /// connect() measures the work of its walks (ManifoldConnection::work; the allocation's pilot).
    bool meter_work = false;
    /// The surface trials run (ConnectionAllocation; false, only where surface solutions are
    /// weighed apart: the straight seed's solution alone, and density() gives the trials' paths
    /// 0 for the same region).
    bool surface_trials = true;
    /// The region runs the surface trials beside failed straight walks too, their finds weighed 1
    /// in MIS (ConnectionAllocation's third kind; as `failed_walk_weight` 1 there, whatever the
    /// setting). density() is told the same for the same region.
    bool failed_walk_trials = false;
    /// The allocation's pilot: where surface solutions are weighed apart and the straight walk
    /// fails beside a clear seed, the surface trials still run, as probes: what they find is
    /// not counted (SolutionSet::probes), but tells the pilot the variance BSDF sampling alone
    /// has for those paths, which it otherwise sees only in its own rare hits.
    bool probes = false;
    /// How the path samples x_b's next direction (BSDF sampling mixed with caster sampling);
    /// null: BSDF sampling alone. Alg. 2's BSDF densities read it.
    const CasterSampling* directions = nullptr;
};

/// What ManifoldTechnique::density tells beside the density, for the MIS weights and the
/// allocation's pilot (ConnectionAllocation).
struct DensityDetail {
    /// Where surface solutions are weighed apart: the path is one only the surface trials reach.
    bool surface_path = false;
    /// c = surface_weight where the density is c times the one the trials find the path with
    /// (ManifoldSolution::weight), else 1.
    double weight = 1;
    /// With `want_probe`: where the technique's density is 0 because the straight walk did not
    /// converge beside a clear seed (the trials do not run there), the density with which the
    /// pilot's probes (ManifoldQuery::probes) find the path; else 0.
    bool want_probe = false;
    double probe = 0;
};

/// One light connection from x_b (ManifoldTechnique::connect).
struct ManifoldConnection {
    enum class Kind {
        None,      ///< no light sample, a blocked or culled seed, or no connection drawn
        Direct,    ///< x_c is in plain sight of x_b (nothing refracts on the segment), f_b > 0: NEE's sample
        Manifold,  ///< the seed path was walked: `set` holds what the walks found
    };
    Kind kind = Kind::None;
    const Light* light = nullptr;  ///< Alg. 1 line 1: the light chosen ...
    double pmf = 0;                ///< ... with this probability ...
    LightSample ls;                ///< ... and the point sampled on it (valid unless kind is None)
    SampledSpectrum f_b;           ///< Kind::Direct: x_b's BSDF towards ls (nonzero)
    /// The probability the connection was made with: MIS weighs each solution by q p_mnee and the
    /// estimate counts it 1 / q (1 for delta lights and for solutions=one's fixed q).
    double q = 1;
    SolutionSet set;  ///< Kind::Manifold: the admissible paths, each f / p of Alg. 1's last line
    double work = 0;  ///< with ManifoldQuery::meter_work: the work of the walks (work_meter.h)
    /// ... and of tracing the seed path, where there is one (q > 0)
    double seed_work = 0;
};

class ManifoldTechnique {
public:
    ManifoldTechnique(const Scene& scene, const MneeSettings& settings) : m_scene(&scene), m_settings(&settings) {}

    /// Alg. 1 whole, from x_b: line 1, the light point (drawn exactly as NEE draws it); line 2,
    /// the seed path (Sec. 3.1); then, with probability q, lines 3-5 for every solution the
    /// estimator finds (solve()). A clear segment is NEE's connection (Kind::Direct), as is every
    /// connection where q = 0, after its one shadow ray.
    ManifoldConnection connect(const ManifoldQuery& query, Sampler& sampler) const;

    /// Alg. 1 lines 3-5 from the seed path `seed` (line 2) to the light point `lp` (line 1, light
    /// `light` chosen with probability `pmf`). Through a dispersive chain with every wavelength
    /// of the path alive (and `spectral_walks`), the chain is solved once per wavelength from
    /// the same seed, each solution weighted as if its wavelength were the hero: BSDF sampling
    /// through such a chain keeps the hero alone, so the slots' weights sum to one per path.
    /// (Starting the other wavelengths' walks from the hero's solution would be cheaper, but the
    /// paths a wavelength finds would then differ from the ones Alg. 2 tests for it.)
    ///
    /// With solutions=all, the straight seed's solution (seeding straight or straight+surface)
    /// and those of `trials` surface seeds, each on a caster CasterChoice picks (surface or
    /// straight+surface), are
    /// solved for the same half vectors, and each distinct admissible path is counted once. The
    /// surface seeds draw one number from `sampler` and their own stream from it, so the
    /// sampler's dimensions stay bounded (primary-sample-space samplers).
    /// `max_k`: the longest chain max_depth allows here (-1: any).
    SolutionSet solve(const ManifoldQuery& q, const Light& light, double pmf, const LightPoint& lp,
                      const std::vector<ManifoldVertex>& seed, Sampler& sampler, int max_k = -1) const;

    /// The technique's area density for the path x_b, chain[0..k), x_c at wavelength `lambda`:
    /// Alg. 2 for solutions=one (0 when the straight seed does not walk to this path); for
    /// solutions=all and unbiased the solution density (solution_density: every solution is the
    /// technique's); with surface_weight c < 1, where the straight seed is clear, the solution
    /// density for the path Alg. 2 walks to, c times it for another path if Alg. 2's walk
    /// converges (to the other), and 0 if it does not converge. A path through an emissive
    /// interface is the straight seed's alone: Alg. 2 whenever the straight seed is walked.
    /// Where surface solutions are weighed apart (MneeSettings::splits_surface_solutions),
    /// `surface_trials` false (a region without them) gives the paths only the trials reach 0,
    /// and `detail` tells whether the path is one of those, and more (DensityDetail).
    /// `failed_walk_trials`: the region's ManifoldQuery::failed_walk_trials.
    double density(const SurfaceInteraction& xb, const BSDF& bsdf_b, const SurfaceInteraction* chain, int k,
                   const Light& light, double pmf, const Vec3& xc, const Vec3& nc, double lambda,
                   bool surface_trials = true, DensityDetail* detail = nullptr, bool failed_walk_trials = false) const;

private:
    const Scene* m_scene;
    const MneeSettings* m_settings;
};

}  // namespace snell
