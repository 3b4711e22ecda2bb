#include "integrators/path/technique_stats.h"

#include "core/stats.h"

namespace snell {

namespace {
StatMoments emitted{"path.technique.emitted", "per-sample luminance seen directly on emitters"};
StatMoments bsdf_hit{"path.technique.bsdf_hit", "per-sample luminance of emitters hit by BSDF sampling"};
StatMoments bsdf_refracted{"path.technique.bsdf_refracted",
                           "per-sample luminance of emitters hit by BSDF sampling through refractive interfaces"};
StatMoments nee{"path.technique.nee", "per-sample luminance of next event estimation"};
StatMoments mnee_straight{"path.technique.mnee_straight", "per-sample luminance of MNEE's straight-seed solutions"};
StatMoments mnee_surface{"path.technique.mnee_surface", "per-sample luminance of MNEE's surface-seed solutions"};
StatMoments total{"path.sample", "per-sample luminance of camera paths (every technique)"};
const std::array<StatMoments*, kTechniqueCount> kStats = {&emitted, &bsdf_hit,      &bsdf_refracted,
                                                          &nee,     &mnee_straight, &mnee_surface};
}  // namespace

const char* technique_name(Technique t) {
    static const char* const names[kTechniqueCount] = {"emitted", "bsdf_hit",      "bsdf_refracted",
                                                       "nee",     "mnee_straight", "mnee_surface"};
    return names[size_t(t)];
}

void TechniqueLog::record() const {
    double sum = 0;
    for (int i = 0; i < kTechniqueCount; ++i) {
        kStats[size_t(i)]->add(y[size_t(i)]);
        sum += y[size_t(i)];
    }
    total.add(sum);
}

}  // namespace snell
