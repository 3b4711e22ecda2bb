#include "integrators/erpt/energy_redistribution.h"

#include <algorithm>
#include <cmath>

#include "core/rng.h"
#include "integrators/pssmlt/primary_sample_sampler.h"

namespace snell {

ChainPlan plan_chains(double e, int mutations, double deposition_energy, int max_chains, double u) {
    ChainPlan plan;
    if (!(e > 0) || !std::isfinite(e) || !(deposition_energy > 0)) return plan;
    const double expected = e / (double(mutations) * deposition_energy);
    if (expected >= double(max_chains)) {
        plan.chains = max_chains;
        plan.quantum = e / (double(max_chains) * double(mutations));
    } else {
        plan.chains = int(std::floor(u + expected));
        plan.quantum = deposition_energy;
    }
    return plan;
}

void redistribute_energy(const std::vector<double>& start, const PathSample& seed, const ChainPlan& plan, int mutations,
                         uint64_t stream_bits, double s1, double s2, const ChainEvaluate& evaluate,
                         const ChainDeposit& deposit) {
    for (int c = 0; c < plan.chains; ++c) {
        PrimarySampleSampler mutator(mix_bits(stream_bits + 0x9e3779b97f4a7c15ULL * uint64_t(c + 1)), uint64_t(c),
                                     /*large_step_probability=*/0.0, s1, s2);
        mutator.set_state(start);
        PathSample current = seed;
        for (int m = 0; m < mutations; ++m) {
            mutator.start_iteration();
            const PathSample proposed = evaluate(mutator);
            const double yc = current.target(), yp = proposed.target();
            double a = std::min(1.0, yp / yc);  // yc > 0: the chain only moves to Y > 0
            if (!(a >= 0)) a = 0;
            if (a < 1) deposit(current, current.xyz * ((1 - a) * plan.quantum / yc));
            if (a > 0) deposit(proposed, proposed.xyz * (a * plan.quantum / yp));
            if (mutator.uniform() < a) {
                current = proposed;
                mutator.accept();
            } else {
                mutator.reject();
            }
        }
    }
}

}  // namespace snell
