#pragma once
// The core of energy redistribution path tracing (Cline, Talbot & Egbert 2005): a seed path of
// energy e starts floor(u + e / (M E_d)) Metropolis chains of M mutations, and every mutation
// deposits the quantum E_d. Started from seeds whose energy is distributed like the image, a
// chain that preserves the target distribution keeps it so after every mutation, so the
// expected deposits form the image whatever M and E_d are (Cline et al.'s energy flow).
// Independent of the renderer: the estimator is a callback, which lets the tests drive it with
// analytic targets.
#include <cstdint>
#include <functional>
#include <vector>

#include "integrators/pssmlt/path_sample.h"

namespace snell {

class PrimarySampleSampler;

/// How a seed's energy is split: `chains` chains whose every mutation deposits `quantum`.
struct ChainPlan {
    int chains = 0;
    double quantum = 0;  ///< luminance Y deposited per mutation
};

/// Cline et al.'s chain count floor(u + e / (M E_d)) for a seed of luminance e, M = mutations,
/// E_d = deposition_energy, u uniform in [0,1): its expectation times M E_d is e. A seed that
/// would start more than max_chains starts max_chains with quantum e / (max_chains M) instead,
/// which deposits exactly e (one extreme path cannot stall a render).
ChainPlan plan_chains(double e, int mutations, double deposition_energy, int max_chains, double u);

/// Target evaluation of the chain's proposal: the callback draws the film position, wavelength
/// and path from the sampler (evaluate(), path_sample.h). Its luminance xyz.y is the Metropolis
/// target; zero keeps the chain out (outside ERPT's `shapes`, say).
using ChainEvaluate = std::function<PathSample(PrimarySampleSampler&)>;
/// Receives a deposit of XYZ `xyz` at the output pixel of `s`.
using ChainDeposit = std::function<void(const PathSample& s, const Vec3& xyz)>;

/// Runs plan.chains chains of `mutations` Kelemen small steps (range [s1, s2], no large steps)
/// from the primary sample `start`, whose evaluation is `seed` (seed.target() > 0). Acceptance
/// is min(1, Y(proposed) / Y(current)); each mutation deposits the quantum split between the
/// current and the proposed state by their probabilities of being the next state (expected
/// values, as in pssmlt), as their XYZ scaled to luminance quantum. Chain c draws from a PCG32
/// stream fixed by (stream_bits, c), so the deposits are a pure function of the arguments.
void redistribute_energy(const std::vector<double>& start, const PathSample& seed, const ChainPlan& plan, int mutations,
                         uint64_t stream_bits, double s1, double s2, const ChainEvaluate& evaluate,
                         const ChainDeposit& deposit);

}  // namespace snell
