#pragma once
// When two manifold walks found the same admissible path (Alg. 2 lines 5-7; the de-duplication
// of several solutions per shading point builds on it).
#include <vector>

#include "core/sampled_spectrum.h"
#include "manifold/manifold_vertex.h"
#include "manifold/manifold_walk.h"

namespace snell {

class Scene;

/// One admissible chain x_1..x_k between x_b and x_c that a light connection found, with what an
/// integrator needs to weight it against the other techniques.
struct ManifoldSolution {
    std::vector<ManifoldVertex> chain;
    /// f(X) / p(X) of Alg. 1 (light pmf included), before MIS: every wavelength slot, or only
    /// `slot`'s when the chain disperses and was solved for that wavelength alone.
    SampledSpectrum value;
    int slot = -1;       ///< wavelength slot the chain was solved for; -1: all of them
    double count = 1;    ///< estimator weight of the solution (1 for the paper's estimator)
    double density = 0;  ///< this technique's area density (Eq. 7 with Eq. 8)
    /// `density` before surface_weight: solution_density_bound of the path, which mis_cutoff reads.
    double bound = 0;
    double pdf_bsdf = 0;        ///< BSDF sampling of the same path from x_b
    double pdf_nee_last = 0;    ///< NEE from x_k (0 unless x_k is rough)
    bool from_surface = false;  ///< walked from a seed sampled on a caster (else the straight seed)
    /// c = surface_weight where `density` is c times the density with which the trials find the
    /// solution (a technique apart in MIS), 1 elsewhere: the pilot of ConnectionAllocation needs
    /// both, one for the MIS weights, the other for how often the solution is drawn.
    double weight = 1;
};

/// What one light connection yields.
struct SolutionSet {
    std::vector<ManifoldSolution> solutions;
    /// With ManifoldQuery::meter_work: the work of the surface trials among the walks (what a
    /// region without them saves; work_meter.h).
    double trial_work = 0;
    /// With ManifoldQuery::probes: the paths the pilot's probes found (not counted), and their
    /// work (no part of ManifoldConnection::work).
    std::vector<ManifoldSolution> probes;
    double probe_work = 0;
};

/// Tolerance of same_solution, relative to the segments next to each vertex.
inline constexpr double kSameSolutionTolerance = 1e-5;

/// A few Newton steps (threshold 1e-13, at most 6, never increasing the error) on a converged
/// chain. A walk stops at its threshold and a traced path carries ray offsets, and near caustics
/// the constraints hardly depend on position; in the quadratic phase a few steps bring two
/// chains of one solution to agree far below kSameSolutionTolerance.
void polish_solution(const Scene* scene, const Vec3& xb, std::vector<ManifoldVertex>& chain, const TangentBasis& xc,
                     const WalkSettings& walk);

/// Whether two (polished) chains between x_b and x_c are the same path: same length, the same
/// shapes in the same order, and every vertex within kSameSolutionTolerance times the shorter of
/// its two adjacent segments (x_0 = x_b, x_{k+1} = x_c) of its counterpart. Scale-free.
bool same_solution(const Vec3& xb, const std::vector<ManifoldVertex>& a, const std::vector<ManifoldVertex>& b,
                   const Vec3& xc);

}  // namespace snell
