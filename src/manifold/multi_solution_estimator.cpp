#include "manifold/multi_solution_estimator.h"

#include "geometry/shape.h"
#include "manifold/seed_path.h"
#include "manifold/surface_seed.h"
#include "manifold/walk_counters.h"
#include "manifold/work_meter.h"

namespace snell {

bool MultiSolutionEstimator::weighs_surface_solutions() const { return m_settings->splits_surface_solutions(); }

void MultiSolutionEstimator::solve(const ManifoldQuery& q, const BSDFContext& ctx, int slot, const Light& light,
                                   double pmf, const LightPoint& lp, const std::vector<ManifoldVertex>& seed,
                                   Sampler& sampler, int max_k, SolutionSet& out) const {
    const size_t before = out.solutions.size();
    HalfVectorDraws draws(sampler);
    bool straight_converged = false;
    // The straight solution is polished (for same_solution) only where trials may refind it:
    // elsewhere the polish is a second walk that changes nothing the image sees (its value is
    // the unpolished chain's; docs/experiments.md, "Cheaper walks on meshes").
    const bool trials_follow =
        m_settings->seeding != MneeSeeding::Straight && (q.surface_trials || !weighs_surface_solutions());
    if (q.straight_seed && walks_straight_seed())
        add_solution(q, ctx, slot, light, pmf, lp, seed, draws, max_k, false, trials_follow, out, &straight_converged);
    if (m_settings->seeding == MneeSeeding::Straight) return;  // settings made in code: no surface seeds
    // surface_weight: beside a clear straight seed, surface solutions count only where the
    // straight walk converged (to another one, or its own): a function of x_b and the light
    // point that density() repeats with Alg. 2's walk. Where it fails (mostly receivers with no
    // solution at all: a shadow), the trials would only fail too, at the cost of full walks.
    const bool weighted = q.straight_seed && weighs_surface_solutions();
    // There, too, only the paths Alg. 2 can tell apart are the technique's: those crossing the
    // straight seed's shapes in its order, refracting at each (density() gives the others 0,
    // BSDF sampling's). A trial that finds another one has failed.
    const Foreign foreign = [&](const std::vector<ManifoldVertex>& chain) {
        if (!weighted) return false;
        if (chain.size() != seed.size()) return true;
        for (size_t i = 0; i < seed.size(); ++i)
            if (chain[i].shape != seed[i].shape || chain[i].reflect) return true;
        return false;
    };
    // A trial's chain starts on the caster it drew a point on (trace_surface_seed), so where
    // only the straight seed's shapes count, only its first shape's trials can find one: the
    // other casters' would all be foreign. That keeps a scene's other glass from costing every
    // connection their trials.
    const Shape* only = weighted && !seed.empty() ? seed.front().shape : nullptr;
    const auto run_trials = [&](size_t first, SolutionSet& into) {
        PCG32 rng = trial_stream(sampler);
        const CasterChoice casters(*m_scene, q.xb->p, ctx.hero(), only);
        if (!casters.empty()) trials_on(q, ctx, slot, light, pmf, lp, casters, rng, draws, max_k, foreign, first, into);
    };
    // Where the straight walk failed the trials' finds weigh failed_walk_weight; at 0 they are
    // BSDF sampling's.
    const double c_f = q.failed_walk_trials ? 1.0 : m_settings->failed_walk_weight;
    if (weighted && !straight_converged && !(c_f > 0)) {
        // The pilot's probes: the paths found here stay BSDF sampling's (density() gives them 0),
        // but the pilot judges BSDF sampling's variance for them from these finds
        // (ConnectionAllocation); their work is no part of a connection's.
        if (q.probes) {
            const double w0 = work_so_far();
            SolutionSet probes;
            run_trials(0, probes);
            for (ManifoldSolution& s : probes.solutions) out.probes.push_back(std::move(s));
            out.probe_work += work_so_far() - w0;
        }
        return;
    }
    // A region without surface trials (ConnectionAllocation) leaves their paths to BSDF sampling:
    // density() gives them 0 there, as it is told.
    if (!q.surface_trials && weighs_surface_solutions()) return;
    const double w0 = q.meter_work ? work_so_far() : 0.0;
    run_trials(before, out);
    if (q.meter_work) out.trial_work += work_so_far() - w0;
    // The solutions the straight seed does not walk to (all found by surface seeds; the straight
    // seed's own is never added twice) weigh c times their density in MIS, as density() answers
    // for their BSDF-sampled copies.
    if (weighted) {
        const double c = straight_converged ? m_settings->surface_weight : c_f;
        for (size_t i = before; i < out.solutions.size(); ++i)
            if (out.solutions[i].from_surface) {
                out.solutions[i].density *= c;
                out.solutions[i].weight = c;
            }
    }
    walk_counters::solutions_per_connection.add(uint32_t(out.solutions.size() - before));
}

namespace {
// Whether the path x_b, x_1..x_k, x_c crosses the straight seed's shapes in its order, refracting
// at each (what a trial beside a clear straight seed may find: solve()'s `foreign`).
bool crosses_as_the_seed(const Vec3& xb, const SurfaceInteraction* chain, int k, const Vec3& xc,
                         const std::vector<ManifoldVertex>& seed) {
    if (size_t(k) != seed.size()) return false;
    for (int i = 0; i < k; ++i) {
        if (chain[i].shape != seed[size_t(i)].shape) return false;
        const Vec3 prev = i == 0 ? xb : chain[i - 1].p, next = i + 1 == k ? xc : chain[i + 1].p;
        if (dot(prev - chain[i].p, chain[i].ng) * dot(next - chain[i].p, chain[i].ng) > 0) return false;
    }
    return true;
}
}  // namespace

double MultiSolutionEstimator::density(const SurfaceInteraction& xb, const BSDF& bsdf_b,
                                       const SurfaceInteraction* chain, int k, const Light& light, double pmf,
                                       const Vec3& xc, const Vec3& nc, double lambda, bool surface_trials,
                                       DensityDetail* detail, bool failed_walk_trials) const {
    DensityDetail none;
    DensityDetail& d = detail ? *detail : none;
    d.surface_path = false;
    d.weight = 1;
    d.probe = 0;
    // With surface seeds alone, a path through an emissive interface is no one's: the solution
    // density gives 0.
    if (walks_straight_seed() && passes_emitter(chain, k))
        return alg2_density(xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda);
    if (!weighs_surface_solutions()) return every_solution_density(xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda);
    // Behind a blocker the full solution density; beside a clear straight seed Alg. 2 for the
    // path its walk reaches (the same value), c times the solution density for another where
    // that walk converges (to the other one), 0 where it does not. solve() counts the same paths
    // with the same weights.
    // The paths only the surface trials reach (behind a blocker, or beside a converged straight
    // walk that reaches another path) are theirs: 0 where the region runs none.
    const StraightSeed seed = trace_straight_seed(*m_scene, xb, xc, lambda, *m_settings);
    if (seed.status != SeedStatus::Refractive) {
        d.surface_path = true;
        return surface_trials ? every_solution_density(xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda, &seed) : 0.0;
    }
    bool converged = false;
    const double reached = alg2_density(xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda, &seed, &converged);
    if (reached > 0) return reached;
    if (!converged) {
        const double c_f = failed_walk_trials ? 1.0 : m_settings->failed_walk_weight;
        if (c_f > 0) {
            // solve() weighs the trials' finds here c_f (the straight seed's shapes in its order).
            if (!crosses_as_the_seed(xb.p, chain, k, xc, seed.chain)) return 0.0;
            d.surface_path = true;
            d.weight = c_f;
            return surface_trials
                       ? c_f * every_solution_density(xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda, &seed)
                       : 0.0;
        }
        // The pilot's probes walk the trials here too (solve()): the density they find it with,
        // for the paths the trials may find (the straight seed's shapes in its order).
        if (d.want_probe && crosses_as_the_seed(xb.p, chain, k, xc, seed.chain))
            d.probe = every_solution_density(xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda, &seed);
        return 0.0;
    }
    d.surface_path = true;
    d.weight = m_settings->surface_weight;
    if (!surface_trials) return 0.0;
    return m_settings->surface_weight * every_solution_density(xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda, &seed);
}

}  // namespace snell
