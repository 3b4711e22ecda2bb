#include <functional>
#include <map>

#include "core/props.h"
#include "integrators/bdpt/bdpt.h"
#include "integrators/direct/direct.h"
#include "integrators/erpt/erpt.h"
#include "integrators/hslt/hslt.h"
#include "integrators/integrator.h"
#include "integrators/mnee/mnee_integrator.h"
#include "integrators/path/path_tracer.h"
#include "integrators/pssmlt/pssmlt.h"

namespace snell {

namespace {
using Factory = std::function<std::shared_ptr<Integrator>(const Props&)>;

// One entry per technique; the key is the scene-file `type` and the name used on the command
// line (`snell compare --integrators ...`).
const std::map<std::string, Factory>& registry() {
    static const std::map<std::string, Factory> r = {
        {"bdpt", [](const Props& p) { return std::make_shared<BdptIntegrator>(PathSettings::from_props(p)); }},
        {"erpt", [](const Props& p) { return std::make_shared<ErptIntegrator>(ErptSettings::from_props(p)); }},
        // Mitsuba's direct illumination integrator.
        {"direct", [](const Props& p) { return std::make_shared<DirectIntegrator>(DirectSettings::from_props(p)); }},
        // `path` means what it means in Mitsuba and pbrt: emitter sampling and BSDF sampling, MIS.
        {"path",
         [](const Props& p) { return std::make_shared<PathTracer>(PathSettings::tracer_from_props(p), true, "path"); }},
        {"nee",
         [](const Props& p) { return std::make_shared<PathTracer>(PathSettings::tracer_from_props(p), true, "nee"); }},
        // The paper's pure path tracing: BSDF sampling alone.
        {"pt",
         [](const Props& p) { return std::make_shared<PathTracer>(PathSettings::tracer_from_props(p), false, "pt"); }},
        {"mnee",
         [](const Props& p) {
             return std::make_shared<MneeIntegrator>(MneeIntegrator::path_settings_from_props(p),
                                                     MneeSettings::from_props(p));
         }},
        {"pssmlt", [](const Props& p) { return std::make_shared<PssmltIntegrator>(PssmltSettings::from_props(p)); }},
        // Half-vector space light transport (Kaplanyan et al. 2014), the paper's last baseline.
        {"hslt", [](const Props& p) { return std::make_shared<HsltIntegrator>(HsltSettings::from_props(p)); }},
    };
    return r;
}
}  // namespace

std::shared_ptr<Integrator> create_integrator(const Props& props) {
    const auto& r = registry();
    auto it = r.find(props.type());
    if (it == r.end()) {
        std::string known;
        for (auto& [k, v] : r) known += (known.empty() ? "" : ", ") + k;
        props.raise("unknown integrator type '" + props.type() + "' (known: " + known + ")");
    }
    auto integ = it->second(props);
    // Every technique: wavelengths per path (1 reproduces the paper's single-wavelength set-up).
    const int64_t n = props.get_int("spectral_samples", kSpectrumSamples);
    if (n < 1 || n > kSpectrumSamples)
        props.raise_param("spectral_samples",
                          "spectral_samples must lie in [1, " + std::to_string(kSpectrumSamples) + "]");
    integ->set_spectral_samples(int(n));
    props.check_unused();
    return integ;
}

}  // namespace snell
