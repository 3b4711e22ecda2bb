#pragma once
// solutions=keyed: the straight seed's solution plus every distinct solution that `trials`
// surface trials walk to, each counted once, with the trials' random numbers (each trial's choice
// of caster among them) drawn from a stream keyed by the connection itself (x_b, the light point,
// the wavelength). Which solutions a connection finds is then a fixed function of the path's endpoints
// and half vectors, and density() replays the same trials for a given path: its MIS density is
// the solution density where one of them (or the straight seed, Alg. 2) walks to the path, and
// 0 where none does, which leaves that path to BSDF sampling. Unbiased, like the paper's Alg. 2
// with more than one deterministic seed, and without the 1 / p estimate of `unbiased`, whose
// rare, heavily counted finds cost it most of a second solution's share (docs/mnee.md).
#include "manifold/estimator_base.h"

namespace snell {

class KeyedTrialsEstimator final : public EstimatorBase {
public:
    using EstimatorBase::EstimatorBase;
    void solve(const ManifoldQuery& q, const BSDFContext& ctx, int slot, const Light& light, double pmf,
               const LightPoint& lp, const std::vector<ManifoldVertex>& seed, Sampler& sampler, int max_k,
               SolutionSet& out) const;
    double density(const SurfaceInteraction& xb, const BSDF& bsdf_b, const SurfaceInteraction* chain, int k,
                   const Light& light, double pmf, const Vec3& xc, const Vec3& nc, double lambda) const;
};

/// The keyed trials' stream for the connection x_b -> x_c at wavelength `lambda`: a function of
/// those alone.
PCG32 keyed_trial_stream(const Vec3& xb, const Vec3& xc, double lambda);

}  // namespace snell
