#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/sampler.h"

namespace snell {

/// What a scene's <sampler> asks for; the renderer builds the sampler once spp is known.
/// `type` is one of sampler_types(); `jitter` is used by `stratified` and `multijitter` only.
struct SamplerSpec {
    std::string type = "independent";
    bool jitter = true;
};

/// The sampler types create_sampler() knows: independent, stratified, multijitter, ldsampler, sobol.
const std::vector<std::string>& sampler_types();

/// Builds the sampler of `spec` for `sample_count` samples per pixel (> 0) and `seed`. The renderer
/// creates it once and clone()s it per tile. Throws std::invalid_argument for an unknown type or a
/// non-positive sample_count.
std::unique_ptr<Sampler> create_sampler(const SamplerSpec& spec, int sample_count, uint64_t seed);

/// The sample count the sampler of `spec` stratifies for when asked for `requested`: Mitsuba's
/// rounding (stratified: next perfect square; multijitter: a cols x rows grid; ldsampler: next
/// power of four, at least 4; independent and sobol: unchanged).
int rounded_sample_count(const SamplerSpec& spec, int requested);

}  // namespace snell
