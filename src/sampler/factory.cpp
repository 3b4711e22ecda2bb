#include "sampler/factory.h"

#include <stdexcept>

#include "sampler/independent.h"
#include "sampler/ldsampler.h"
#include "sampler/multijitter.h"
#include "sampler/orthogonal.h"
#include "sampler/sobol.h"
#include "sampler/stratified.h"

namespace snell {

const std::vector<std::string>& sampler_types() {
    static const std::vector<std::string> types = {"independent", "stratified", "multijitter",
                                                   "orthogonal",  "ldsampler",  "sobol"};
    return types;
}

std::unique_ptr<Sampler> create_sampler(const SamplerSpec& spec, int sample_count, uint64_t seed) {
    if (sample_count <= 0) throw std::invalid_argument("create_sampler: sample_count must be positive");
    if (spec.type == "independent") return std::make_unique<IndependentSampler>(seed);
    if (spec.type == "stratified") return std::make_unique<StratifiedSampler>(sample_count, seed, spec.jitter);
    if (spec.type == "multijitter") return std::make_unique<MultiJitterSampler>(sample_count, seed, spec.jitter);
    if (spec.type == "orthogonal") return std::make_unique<OrthogonalSampler>(sample_count, seed, spec.jitter);
    if (spec.type == "ldsampler") return std::make_unique<LowDiscrepancySampler>(sample_count, seed);
    if (spec.type == "sobol") return std::make_unique<SobolSampler>(sample_count, seed);
    throw std::invalid_argument("create_sampler: unknown sampler type '" + spec.type + "'");
}

int rounded_sample_count(const SamplerSpec& spec, int requested) {
    if (requested <= 0) throw std::invalid_argument("rounded_sample_count: sample count must be positive");
    if (spec.type == "stratified") return StratifiedSampler::round_sample_count(requested);
    if (spec.type == "multijitter") return MultiJitterSampler::round_sample_count(requested);
    if (spec.type == "orthogonal") return OrthogonalSampler::round_sample_count(requested);
    if (spec.type == "ldsampler") return LowDiscrepancySampler::round_sample_count(requested);
    if (spec.type == "independent" || spec.type == "sobol") return requested;
    throw std::invalid_argument("rounded_sample_count: unknown sampler type '" + spec.type + "'");
}

}  // namespace snell
