#include "integrators/path/technique_stats.h"

#include <iterator>

#include "core/stats.h"
#include "render/sample_tracer.h"

namespace snell {

namespace {
StatMoments emitted{"path.technique.emitted", "per-sample luminance seen directly on emitters"};
StatMoments bsdf_hit{"path.technique.bsdf_hit", "per-sample luminance of emitters hit by BSDF sampling"};
StatMoments bsdf_refracted{"path.technique.bsdf_refracted",
                           "per-sample luminance of emitters hit by BSDF sampling through refractive interfaces"};
StatMoments bsdf_reflected{
    "path.technique.bsdf_reflected",
    "per-sample luminance of emitters hit by BSDF sampling through interfaces with a reflection"};
StatMoments nee{"path.technique.nee", "per-sample luminance of next event estimation"};
StatMoments mnee_straight{"path.technique.mnee_straight", "per-sample luminance of MNEE's straight-seed solutions"};
StatMoments mnee_surface{"path.technique.mnee_surface", "per-sample luminance of MNEE's surface-seed solutions"};
StatMoments mnee_reflected{"path.technique.mnee_reflected",
                           "per-sample luminance of MNEE's connections reflected off the outside of glass"};
StatMoments total{"path.sample", "per-sample luminance of camera paths (every technique)"};
// In Technique's order; the size check keeps a new technique from reading a missing entry.
StatMoments* const kStats[] = {&emitted, &bsdf_hit,      &bsdf_refracted, &bsdf_reflected,
                               &nee,     &mnee_straight, &mnee_surface,   &mnee_reflected};
static_assert(std::size(kStats) == size_t(kTechniqueCount));
}  // namespace

const char* technique_name(Technique t) {
    static const char* const names[] = {"emitted", "bsdf_hit",      "bsdf_refracted", "bsdf_reflected",
                                        "nee",     "mnee_straight", "mnee_surface",   "mnee_reflected"};
    static_assert(std::size(names) == size_t(kTechniqueCount));
    return names[size_t(t)];
}

std::vector<std::string> path_technique_names() {
    std::vector<std::string> names;
    for (int t = 0; t < kTechniqueCount; ++t) names.emplace_back(technique_name(Technique(t)));
    return names;
}

int TechniqueLog::record(const SampledWavelengths& wl) const {
    double sum = 0, largest = 0;
    int largest_technique = -1;
    for (int i = 0; i < kTechniqueCount; ++i) {
        const SampledSpectrum& v = m_by[size_t(i)];
        if (v.is_zero()) {
            kStats[size_t(i)]->add_zero();
            continue;
        }
        const double y = wl.to_xyz(v).y;
        kStats[size_t(i)]->add(y);
        sum += y;
        if (y > largest) {
            largest = y;
            largest_technique = i;
        }
    }
    total.add(sum);
    return largest_technique;
}

}  // namespace snell
