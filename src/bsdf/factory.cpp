// create_bsdf: reads Mitsuba-style parameters for every BSDF plugin and reports unknown types,
// bad values and unused parameters with their position in the scene file.
#include "bsdf/factory.h"

#include <algorithm>

#include <cmath>

#include "bsdf/blend.h"
#include "bsdf/conductor.h"
#include "bsdf/dielectric.h"
#include "bsdf/diffuse.h"
#include "bsdf/null_bsdf.h"
#include "bsdf/plastic.h"
#include "bsdf/roughconductor.h"
#include "bsdf/roughdielectric.h"
#include "bsdf/roughplastic.h"
#include "bsdf/thindielectric.h"
#include "bsdf/twosided.h"

namespace snell {

namespace {

/// Below this roughness (both alphas) a rough dielectric or conductor is built as the smooth one.
constexpr double kEffectivelySmoothAlpha = 1e-3;

/// An IOR given as a number or as one of Mitsuba's names ("water", "bk7", ...).
double read_ior(const Props& p, const std::string& name, const std::string& def) {
    if (p.is_string(name)) {
        const std::string s = p.get_string(name);
        try {
            return named_ior(s);
        } catch (const std::invalid_argument& e) {
            p.raise_param(name, e.what());
        }
    }
    const double v = p.has(name) ? p.get_float(name) : named_ior(def);
    if (!(v > 0) || !std::isfinite(v)) p.raise_param(name, "'" + name + "' must be positive");
    return v;
}

struct DielectricParams {
    Spectrum int_ior, ext_ior, specular_reflectance, specular_transmittance;
    std::optional<Spectrum> sigma_a;
};

/// Parameters shared by dielectric, thindielectric and roughdielectric.
DielectricParams read_dielectric(const Props& p, bool extensions) {
    DielectricParams d;
    const double int_ior = read_ior(p, "int_ior", "bk7");
    const double ext_ior = read_ior(p, "ext_ior", "air");
    double abbe = 0;
    if (extensions) {
        abbe = p.get_float("abbe", 0.0);
        if (abbe < 0 || !std::isfinite(abbe)) p.raise_param("abbe", "'abbe' must be >= 0 (0: no dispersion)");
        if (p.has("sigma_a")) d.sigma_a = p.get_spectrum("sigma_a", SpectrumUse::Unbounded);
    }
    d.int_ior = Spectrum::from_ior_abbe(int_ior, abbe);
    d.ext_ior = Spectrum::constant(ext_ior);
    d.specular_reflectance = p.get_spectrum("specular_reflectance", SpectrumUse::Reflectance, Spectrum::constant(1.0));
    d.specular_transmittance =
        p.get_spectrum("specular_transmittance", SpectrumUse::Reflectance, Spectrum::constant(1.0));
    return d;
}

MicrofacetDistribution read_distribution(const Props& p) {
    const std::string name = p.get_string("distribution", "beckmann");
    MicrofacetDistribution::Type type;
    if (name == "beckmann")
        type = MicrofacetDistribution::Type::Beckmann;
    else if (name == "ggx")
        type = MicrofacetDistribution::Type::GGX;
    else
        p.raise_param("distribution", "unknown distribution '" + name + "' (expected beckmann or ggx)");
    double au, av;
    if (p.has("alpha_u") || p.has("alpha_v")) {
        if (p.has("alpha")) p.raise_param("alpha", "give either 'alpha' or 'alpha_u'/'alpha_v', not both");
        au = p.get_float("alpha_u");
        av = p.get_float("alpha_v");
    } else {
        au = av = p.get_float("alpha", 0.1);
    }
    for (auto [v, n] : {std::pair{au, "alpha_u"}, std::pair{av, "alpha_v"}})
        if (!(v >= 0) || !std::isfinite(v))
            p.raise_param(p.has(n) ? n : "alpha", "roughness must be a finite non-negative number");
    return MicrofacetDistribution(type, au, av, p.get_bool("sample_visible", true));
}

/// Mitsuba: `material` names a tabulated metal, or eta/k are given directly.
std::optional<ConductorIOR> read_conductor(const Props& p) {
    if (p.has("eta") || p.has("k")) {
        if (p.has("material")) p.raise_param("material", "give either 'material' or 'eta'/'k', not both");
        ConductorIOR ior{p.get_spectrum("eta", SpectrumUse::Unbounded, Spectrum::constant(0.0)),
                         p.get_spectrum("k", SpectrumUse::Unbounded, Spectrum::constant(1.0))};
        return ior;
    }
    const std::string name = p.get_string("material", "none");
    if (name == "none") return std::nullopt;
    auto ior = named_conductor(name);
    if (!ior) p.raise_param("material", "unknown conductor '" + name + "' (known: " + named_conductor_list() + ")");
    return ior;
}

std::shared_ptr<BSDF> build(const Props& p) {
    const std::string& type = p.type();
    if (type == "diffuse") {
        return std::make_shared<DiffuseBSDF>(
            p.get_spectrum("reflectance", SpectrumUse::Reflectance, Spectrum::constant(0.5)));
    }
    if (type == "dielectric") {
        auto d = read_dielectric(p, true);
        return std::make_shared<DielectricBSDF>(d.int_ior, d.ext_ior, d.specular_reflectance, d.specular_transmittance,
                                                d.sigma_a);
    }
    if (type == "thindielectric") {
        auto d = read_dielectric(p, false);
        return std::make_shared<ThinDielectricBSDF>(d.int_ior, d.ext_ior, d.specular_reflectance,
                                                    d.specular_transmittance);
    }
    if (type == "roughdielectric") {
        auto distr = read_distribution(p);
        auto d = read_dielectric(p, true);
        // Effectively smooth (pbrt-v4's rule): a microfacet lobe this narrow is a delta lobe that
        // the rough model can only evaluate badly, so it becomes the smooth interface; a scene
        // switches between smooth and rough glass with its alpha alone (-D alpha=0).
        if (std::max(distr.alpha_u(), distr.alpha_v()) < kEffectivelySmoothAlpha)
            return std::make_shared<DielectricBSDF>(d.int_ior, d.ext_ior, d.specular_reflectance,
                                                    d.specular_transmittance, d.sigma_a);
        return std::make_shared<RoughDielectricBSDF>(distr, d.int_ior, d.ext_ior, d.specular_reflectance,
                                                     d.specular_transmittance, d.sigma_a);
    }
    if (type == "conductor") {
        auto ior = read_conductor(p);
        return std::make_shared<ConductorBSDF>(
            ior, p.get_spectrum("specular_reflectance", SpectrumUse::Reflectance, Spectrum::constant(1.0)));
    }
    if (type == "roughconductor") {
        auto distr = read_distribution(p);
        auto ior = read_conductor(p);
        if (std::max(distr.alpha_u(), distr.alpha_v()) < kEffectivelySmoothAlpha)
            return std::make_shared<ConductorBSDF>(
                ior, p.get_spectrum("specular_reflectance", SpectrumUse::Reflectance, Spectrum::constant(1.0)));
        return std::make_shared<RoughConductorBSDF>(
            distr, ior, p.get_spectrum("specular_reflectance", SpectrumUse::Reflectance, Spectrum::constant(1.0)));
    }
    if (type == "plastic") {
        const double int_ior = read_ior(p, "int_ior", "polypropylene");
        const double ext_ior = read_ior(p, "ext_ior", "air");
        return std::make_shared<PlasticBSDF>(
            p.get_spectrum("diffuse_reflectance", SpectrumUse::Reflectance, Spectrum::constant(0.5)),
            p.get_spectrum("specular_reflectance", SpectrumUse::Reflectance, Spectrum::constant(1.0)), int_ior, ext_ior,
            p.get_bool("nonlinear", false));
    }
    if (type == "roughplastic") {
        auto distr = read_distribution(p);
        const double int_ior = read_ior(p, "int_ior", "polypropylene");
        const double ext_ior = read_ior(p, "ext_ior", "air");
        auto diffuse = p.get_spectrum("diffuse_reflectance", SpectrumUse::Reflectance, Spectrum::constant(0.5));
        auto specular = p.get_spectrum("specular_reflectance", SpectrumUse::Reflectance, Spectrum::constant(1.0));
        const bool nonlinear = p.get_bool("nonlinear", false);
        if (std::max(distr.alpha_u(), distr.alpha_v()) < kEffectivelySmoothAlpha)
            return std::make_shared<PlasticBSDF>(diffuse, specular, int_ior, ext_ior, nonlinear);
        return std::make_shared<RoughPlasticBSDF>(distr, diffuse, specular, int_ior, ext_ior, nonlinear);
    }
    if (type == "null") return std::make_shared<NullBSDF>();
    if (type == "blendbsdf" || type == "mask") {
        // blendbsdf: (1 - weight) first + weight second; mask: opacity times the nested BSDF,
        // the rest passes through (null).
        const char* param = type == "mask" ? "opacity" : "weight";
        const double w = p.get_float(param, 0.5);
        if (!(w >= 0 && w <= 1)) p.raise_param(param, std::string(param) + " must lie in [0, 1]");
        auto kids = p.children<BSDF>();
        if (type == "mask") {
            if (kids.size() != 1) p.raise("mask needs exactly one nested BSDF");
            return std::make_shared<BlendBSDF>(w, std::make_shared<NullBSDF>(), kids[0]);
        }
        if (kids.size() != 2) p.raise("blendbsdf needs exactly two nested BSDFs");
        return std::make_shared<BlendBSDF>(w, kids[0], kids[1]);
    }
    if (type == "twosided") {
        auto kids = p.children<BSDF>();
        if (kids.empty() || kids.size() > 2) p.raise("twosided needs one or two nested BSDFs");
        for (auto& k : kids)
            if (k->is_transmissive()) p.raise("twosided: only BSDFs without transmission can be nested");
        return std::make_shared<TwoSidedBSDF>(kids[0], kids.size() == 2 ? kids[1] : nullptr);
    }
    p.raise("unknown BSDF type '" + type +
            "' (known: diffuse, dielectric, thindielectric, roughdielectric, conductor, "
            "roughconductor, plastic, roughplastic, twosided, blendbsdf, mask, null)");
}

}  // namespace

std::shared_ptr<BSDF> create_bsdf(const Props& props) {
    auto bsdf = build(props);
    props.check_unused();
    bsdf->set_id(props.id());
    return bsdf;
}

}  // namespace snell
