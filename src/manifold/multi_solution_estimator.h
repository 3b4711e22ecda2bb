#pragma once
// What the estimators of several solutions per light sample share (solutions=all and unbiased):
// the straight seed's solution (with seeding=straight+surface) and those of surface trials, each
// on a caster CasterChoice picks, for the same half vectors; their MIS density is the solution density in the
// technique's domain, and with surface_weight c < 1, beside a clear straight seed, the paths
// the straight seed does not walk to weigh c times it (MneeSettings::surface_weight).
#include "manifold/estimator_base.h"

namespace snell {

class MultiSolutionEstimator : public EstimatorBase {
public:
    using EstimatorBase::EstimatorBase;
    virtual ~MultiSolutionEstimator() = default;
    void solve(const ManifoldQuery& q, const BSDFContext& ctx, int slot, const Light& light, double pmf,
               const LightPoint& lp, const std::vector<ManifoldVertex>& seed, Sampler& sampler, int max_k,
               SolutionSet& out) const;
    /// The solution density; with surface_weight c < 1, where the straight seed is clear, Alg. 2
    /// for the path its walk reaches, c times the solution density for another where that walk
    /// converges (to the other), 0 where it does not. A path through an emissive interface is
    /// the straight seed's alone (Alg. 2) whenever the straight seed is walked. With surface
    /// solutions weighed apart, `surface_trials` false gives the surface trials' paths 0 (a
    /// region without them, ManifoldQuery::surface_trials) and `surface_path` tells whether the
    /// path is theirs, with the rest of DensityDetail.
    double density(const SurfaceInteraction& xb, const BSDF& bsdf_b, const SurfaceInteraction* chain, int k,
                   const Light& light, double pmf, const Vec3& xc, const Vec3& nc, double lambda,
                   bool surface_trials = true, DensityDetail* detail = nullptr, bool failed_walk_trials = false) const;

protected:
    /// The estimator's use of the surface trials, each on a caster `casters` picks.
    virtual void trials_on(const ManifoldQuery& q, const BSDFContext& ctx, int slot, const Light& light, double pmf,
                           const LightPoint& lp, const CasterChoice& casters, PCG32& rng, HalfVectorDraws& draws,
                           int max_k, const Foreign& foreign, size_t before, SolutionSet& out) const = 0;

private:
    /// surface_weight < 1 with both kinds of seeds: beside a clear straight seed the surface
    /// solutions weigh c times their density, and count only where the straight walk converged.
    /// solve() and density() both ask this.
    bool weighs_surface_solutions() const;
};

}  // namespace snell
