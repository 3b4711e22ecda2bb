#pragma once
// What every MNEE estimator (straight_seed_estimator.h, all_solutions_estimator.h,
// unbiased_estimator.h, fallback_estimator.h) is built from: one walk of Alg. 1 turned into a
// solution, a surface-seed trial, and the two ways of using trials (walk every one, or count the
// trials until a solution is found again). ManifoldTechnique picks the estimator from the
// settings and runs it once per wavelength through dispersive chains.
#include <functional>
#include <vector>

#include "core/rng.h"
#include "manifold/caster_choice.h"
#include "manifold/manifold_technique.h"

namespace snell {

class EstimatorBase {
public:
    EstimatorBase(const Scene& scene, const MneeSettings& settings) : m_scene(&scene), m_settings(&settings) {}

protected:
    /// A chain found by a surface trial that the estimator does not count (surface_weight).
    using Foreign = std::function<bool(const std::vector<ManifoldVertex>&)>;

    /// Walks `chain` (its seed) and adds the admissible, visible path unless `out` holds it
    /// (`dedupe`: polished and compared with the solutions already found); returns the index of
    /// the added solution, or -1. `walk_converged`: whether the walk converged, whatever became
    /// of the path.
    int add_solution(const ManifoldQuery& q, const BSDFContext& ctx, int slot, const Light& light, double pmf,
                     const LightPoint& lp, std::vector<ManifoldVertex> chain, HalfVectorDraws& draws, int max_k,
                     bool from_surface, bool dedupe, SolutionSet& out, bool* walk_converged = nullptr) const;
    /// One surface seed, on a caster `casters` picks, walked to a polished admissible path; false
    /// if it fails.
    /// `trace_smooth`: the seeds are traced about the shading normals (the walk still solves for
    /// `draws`), so that which seed is walked does not depend on the half vectors of slots the
    /// path does not have (the keyed estimator replays trials for a given path).
    bool surface_trial(const ManifoldQuery& q, const BSDFContext& ctx, const CasterChoice& casters, PCG32& rng,
                       const LightPoint& lp, HalfVectorDraws& draws, int max_k, std::vector<ManifoldVertex>* chain,
                       bool trace_smooth = false) const;
    /// `trials` surface trials, every new solution among them added, counted once
    /// (solutions=all).
    void walk_every_trial(const ManifoldQuery& q, const BSDFContext& ctx, int slot, const Light& light, double pmf,
                          const LightPoint& lp, const CasterChoice& casters, PCG32& rng, HalfVectorDraws& draws,
                          int max_k, const Foreign& foreign, size_t before, SolutionSet& out) const;
    /// A first round of `trials` surface trials, every new solution Y among them
    /// added and counted by the rounds of further trials until one finds Y again (the unbiased
    /// 1 / p estimate; solutions=unbiased, and fallback behind a blocker).
    void count_trials_to_refind(const ManifoldQuery& q, const BSDFContext& ctx, int slot, const Light& light,
                                double pmf, const LightPoint& lp, const CasterChoice& casters, PCG32& rng,
                                HalfVectorDraws& draws, int max_k, const Foreign& foreign, size_t before,
                                SolutionSet& out) const;
    /// With seeding=surface alone the straight seed is not walked.
    bool walks_straight_seed() const { return m_settings->seeding != MneeSeeding::Surface; }
    /// The surface seeds' own stream, drawn with one number from the sampler (so that the
    /// sampler's dimensions stay bounded for primary-sample-space samplers).
    static PCG32 trial_stream(Sampler& sampler);
    /// Alg. 2 (the straight seed's density), with the seed traced already when `seed` is given.
    double alg2_density(const SurfaceInteraction& xb, const BSDF& bsdf_b, const SurfaceInteraction* chain, int k,
                        const Light& light, double pmf, const Vec3& xc, const Vec3& nc, double lambda,
                        const StraightSeed* seed = nullptr, bool* walk_converged = nullptr) const;
    /// The solution density (Alg. 2 without its walk), in the technique's domain.
    double every_solution_density(const SurfaceInteraction& xb, const BSDF& bsdf_b, const SurfaceInteraction* chain,
                                  int k, const Light& light, double pmf, const Vec3& xc, const Vec3& nc, double lambda,
                                  const StraightSeed* seed = nullptr) const;

    const Scene* m_scene;
    const MneeSettings* m_settings;
};

/// Whether the path x_1..x_k passes an emissive interface: such paths are the straight seed's
/// alone (surface seeds neither start on nor pass such a shape, surface_seed.cpp).
bool passes_emitter(const SurfaceInteraction* chain, int k);

}  // namespace snell
