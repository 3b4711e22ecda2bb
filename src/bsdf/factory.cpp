// create_bsdf: reads Mitsuba-style parameters for every BSDF plugin and reports unknown types,
// bad values and unused parameters with their position in the scene file.
#include "bsdf/factory.h"

#include <algorithm>

#include <cmath>

#include "bsdf/blend.h"
#include "bsdf/bumpmap.h"
#include "bsdf/conductor.h"
#include "bsdf/dielectric.h"
#include "bsdf/diffuse.h"
#include "bsdf/normalmap.h"
#include "bsdf/null_bsdf.h"
#include "bsdf/plastic.h"
#include "bsdf/principled.h"
#include "bsdf/principledthin.h"
#include "bsdf/roughconductor.h"
#include "bsdf/roughdielectric.h"
#include "bsdf/roughplastic.h"
#include "bsdf/thindielectric.h"
#include "bsdf/twosided.h"
#include "texture/constant.h"
#include "texture/factory.h"

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

/// A colour parameter (reflectance-like, default grey `def`): constant or textured.
SpectrumParam colour(const Props& p, const char* name, double def) {
    return get_texture(p, name, SpectrumUse::Reflectance, Spectrum::constant(def));
}

struct DielectricParams {
    Spectrum int_ior, ext_ior;
    SpectrumParam specular_reflectance = Spectrum::constant(1.0), specular_transmittance = Spectrum::constant(1.0);
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
    d.specular_reflectance = colour(p, "specular_reflectance", 1.0);
    d.specular_transmittance = colour(p, "specular_transmittance", 1.0);
    return d;
}

/// The distribution with its constant alphas; textured alphas (roughconductor, roughdielectric,
/// as Mitsuba allows) in *alpha_u / *alpha_v when those are given.
MicrofacetParam read_distribution(const Props& p, bool textures) {
    const std::string name = p.get_string("distribution", "beckmann");
    MicrofacetDistribution::Type type;
    if (name == "beckmann")
        type = MicrofacetDistribution::Type::Beckmann;
    else if (name == "ggx")
        type = MicrofacetDistribution::Type::GGX;
    else
        p.raise_param("distribution", "unknown distribution '" + name + "' (expected beckmann or ggx)");
    auto given = [&](const char* n) { return p.has(n) || (textures && p.named_child<const Texture>(n)); };
    auto read = [&](const char* n, double def) -> TextureRef {
        if (textures) return get_float_texture(p, n, def, 0.0, kInfinity);
        const double v = p.get_float(n, def);
        if (!(v >= 0) || !std::isfinite(v)) p.raise_param(n, "roughness must be a finite non-negative number");
        return ConstantTexture::make(v);
    };
    TextureRef au, av;
    if (given("alpha_u") || given("alpha_v")) {
        if (given("alpha")) p.raise_param("alpha", "give either 'alpha' or 'alpha_u'/'alpha_v', not both");
        if (!given("alpha_u") || !given("alpha_v")) p.raise("give both 'alpha_u' and 'alpha_v'");
        au = read("alpha_u", 0.1);
        av = read("alpha_v", 0.1);
    } else {
        au = av = read("alpha", 0.1);
    }
    // The constant alphas; a texture's are its mean (only where untextured do they count).
    const MicrofacetDistribution base(type, au->mean(), av->mean(), p.get_bool("sample_visible", true));
    return MicrofacetParam(base, au->is_constant() ? nullptr : au, av->is_constant() ? nullptr : av);
}

/// Below this roughness everywhere a rough model is built as the smooth one.
bool effectively_smooth(const MicrofacetParam& d) {
    return d.is_constant() && std::max(d.base().alpha_u(), d.base().alpha_v()) < kEffectivelySmoothAlpha;
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

/// The SMS code's normalmap form: `filename` (the normals as stored, EXR or PNG), `tiles` (uv
/// scale); `use_slopes` and the LEAN fallback settings are accepted (docs/scene-format.md).
TextureRef sms_normal_map(const Props& p) {
    Props t("texture", "bitmap", p.loc());
    t.set("filename", p.get_string("filename"), p.loc());
    t.set("__base_dir", p.get_string("__base_dir", ""), p.loc());
    t.set("raw", true, p.loc());
    const double tiles = p.get_float("tiles", 1.0);
    if (!(tiles > 0) || !std::isfinite(tiles)) p.raise_param("tiles", "tiles must be positive");
    t.set("to_uv", Transform::scale(Vec3(tiles, tiles, 1)), p.loc());
    for (const char* n : {"use_slopes", "lean_fallback", "lean_fallback_alpha", "lean_fallback_material"})
        p.mark_used(n);
    return create_texture(t);
}

std::shared_ptr<BSDF> build(const Props& p) {
    const std::string& type = p.type();
    if (type == "diffuse") {
        return std::make_shared<DiffuseBSDF>(colour(p, "reflectance", 0.5));
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
        auto distr = read_distribution(p, true);
        auto d = read_dielectric(p, true);
        // Effectively smooth (pbrt-v4's rule): a microfacet lobe this narrow is a delta lobe that
        // the rough model can only evaluate badly, so it becomes the smooth interface; a scene
        // switches between smooth and rough glass with its alpha alone (-D alpha=0).
        if (effectively_smooth(distr))
            return std::make_shared<DielectricBSDF>(d.int_ior, d.ext_ior, d.specular_reflectance,
                                                    d.specular_transmittance, d.sigma_a);
        return std::make_shared<RoughDielectricBSDF>(distr, d.int_ior, d.ext_ior, d.specular_reflectance,
                                                     d.specular_transmittance, d.sigma_a);
    }
    if (type == "conductor") {
        auto ior = read_conductor(p);
        return std::make_shared<ConductorBSDF>(ior, colour(p, "specular_reflectance", 1.0));
    }
    if (type == "roughconductor") {
        auto distr = read_distribution(p, true);
        auto ior = read_conductor(p);
        if (effectively_smooth(distr))
            return std::make_shared<ConductorBSDF>(ior, colour(p, "specular_reflectance", 1.0));
        return std::make_shared<RoughConductorBSDF>(distr, ior, colour(p, "specular_reflectance", 1.0));
    }
    if (type == "plastic") {
        const double int_ior = read_ior(p, "int_ior", "polypropylene");
        const double ext_ior = read_ior(p, "ext_ior", "air");
        return std::make_shared<PlasticBSDF>(colour(p, "diffuse_reflectance", 0.5),
                                             colour(p, "specular_reflectance", 1.0), int_ior, ext_ior,
                                             p.get_bool("nonlinear", false));
    }
    if (type == "roughplastic") {
        // Mitsuba's roughplastic takes a constant alpha (its tables depend on it).
        auto distr = read_distribution(p, false);
        const double int_ior = read_ior(p, "int_ior", "polypropylene");
        const double ext_ior = read_ior(p, "ext_ior", "air");
        auto diffuse = colour(p, "diffuse_reflectance", 0.5);
        auto specular = colour(p, "specular_reflectance", 1.0);
        const bool nonlinear = p.get_bool("nonlinear", false);
        if (effectively_smooth(distr))
            return std::make_shared<PlasticBSDF>(diffuse, specular, int_ior, ext_ior, nonlinear);
        return std::make_shared<RoughPlasticBSDF>(distr.base(), diffuse, specular, int_ior, ext_ior, nonlinear);
    }
    if (type == "null") return std::make_shared<NullBSDF>();
    if (type == "blendbsdf" || type == "mask") {
        // blendbsdf: (1 - weight) first + weight second; mask: opacity times the nested BSDF,
        // the rest passes through (null).
        const char* param = type == "mask" ? "opacity" : "weight";
        const TextureRef w = get_float_texture(p, param, 0.5, 0.0, 1.0);
        auto kids = p.children<BSDF>();
        if (type == "mask") {
            if (kids.size() != 1) p.raise("mask needs exactly one nested BSDF");
            return std::make_shared<BlendBSDF>(w, std::make_shared<NullBSDF>(), kids[0]);
        }
        if (kids.size() != 2) p.raise("blendbsdf needs exactly two nested BSDFs");
        return std::make_shared<BlendBSDF>(w, kids[0], kids[1]);
    }
    if (type == "principled") {
        PrincipledBSDF::Params q;
        q.base_color = get_texture(p, "base_color", SpectrumUse::Reflectance, Spectrum::constant(0.5));
        auto given = [&](const char* n) { return p.has(n) || p.named_child<const Texture>(n); };
        // Mitsuba turns a lobe on when its parameter is given and not the float 0.
        auto on = [&](const char* n) { return p.named_child<const Texture>(n) || (p.has(n) && p.get_float(n) != 0.0); };
        auto unit = [&](const char* n, double def) { return get_float_texture(p, n, def, 0.0, 1.0); };
        q.roughness = unit("roughness", 0.5);
        q.anisotropic = unit("anisotropic", 0.0);
        q.metallic = unit("metallic", 0.0);
        q.spec_trans = unit("spec_trans", 0.0);
        q.spec_tint = unit("spec_tint", 0.0);
        q.sheen = unit("sheen", 0.0);
        q.sheen_tint = unit("sheen_tint", 0.0);
        q.flatness = unit("flatness", 0.0);
        q.clearcoat = unit("clearcoat", 0.0);
        q.clearcoat_gloss = unit("clearcoat_gloss", 0.0);
        q.anisotropic_on = on("anisotropic");
        q.spec_trans_on = on("spec_trans");
        q.clearcoat_on = on("clearcoat");
        if (given("eta") && given("specular")) p.raise_param("specular", "give either 'eta' or 'specular', not both");
        if (p.has("eta")) {
            q.eta = p.get_float("eta");
            if (!(q.eta > 0) || !std::isfinite(q.eta)) p.raise_param("eta", "eta must be positive");
            if (q.spec_trans_on && q.eta == 1.0) q.eta = 1.001;  // Mitsuba: no transmission at eta 1
        } else {
            double specular = p.get_float("specular", 0.5);
            if (!(specular >= 0 && specular < 12.5)) p.raise_param("specular", "specular must lie in [0, 12.5)");
            if (q.spec_trans_on && specular == 0) specular = 1e-3;
            q.eta = PrincipledBSDF::eta_from_specular(specular);
        }
        for (auto [n, slot] : {std::pair{"main_specular_sampling_rate", &q.spec_srate},
                               std::pair{"clearcoat_sampling_rate", &q.clearcoat_srate},
                               std::pair{"diffuse_reflectance_sampling_rate", &q.diffuse_srate}}) {
            *slot = p.get_float(n, 1.0);
            if (!(*slot >= 0) || !std::isfinite(*slot)) p.raise_param(n, std::string(n) + " must be >= 0");
        }
        return std::make_shared<PrincipledBSDF>(std::move(q));
    }
    if (type == "principledthin") {
        PrincipledThinBSDF::Params q;
        q.base_color = get_texture(p, "base_color", SpectrumUse::Reflectance, Spectrum::constant(0.5));
        auto on = [&](const char* n) { return p.named_child<const Texture>(n) || (p.has(n) && p.get_float(n) != 0.0); };
        auto unit = [&](const char* n, double def) { return get_float_texture(p, n, def, 0.0, 1.0); };
        q.roughness = unit("roughness", 0.5);
        q.anisotropic = unit("anisotropic", 0.0);
        q.spec_trans = unit("spec_trans", 0.0);
        q.spec_tint = unit("spec_tint", 0.0);
        q.sheen = unit("sheen", 0.0);
        q.sheen_tint = unit("sheen_tint", 0.0);
        q.flatness = unit("flatness", 0.0);
        q.diff_trans = get_float_texture(p, "diff_trans", 0.0, 0.0, 2.0);  // Burley's range
        q.eta = get_float_texture(p, "eta", 1.5, 1e-3, 10.0);
        q.anisotropic_on = on("anisotropic");
        q.spec_trans_on = on("spec_trans");
        q.diff_trans_on = on("diff_trans");
        for (auto [n, slot] : {std::pair{"specular_reflectance_sampling_rate", &q.spec_refl_srate},
                               std::pair{"specular_transmittance_sampling_rate", &q.spec_trans_srate},
                               std::pair{"diffuse_reflectance_sampling_rate", &q.diff_refl_srate},
                               std::pair{"diffuse_transmittance_sampling_rate", &q.diff_trans_srate}}) {
            *slot = p.get_float(n, 1.0);
            if (!(*slot >= 0) || !std::isfinite(*slot)) p.raise_param(n, std::string(n) + " must be >= 0");
        }
        return std::make_shared<PrincipledThinBSDF>(std::move(q));
    }
    if (type == "normalmap" || type == "bumpmap") {
        auto kids = p.children<BSDF>();
        if (kids.size() != 1) p.raise(type + " needs exactly one nested BSDF");
        // Mitsuba 3's corrections default to on; the SMS code's normalmap (Mitsuba 2) has neither.
        const bool sms_form = type == "normalmap" && !p.named_child<const Texture>("normalmap") && p.has("filename");
        PerturbedFrameBSDF::Options opt;
        opt.flip_invalid_normals = p.get_bool("flip_invalid_normals", !sms_form);
        opt.shadowing = p.get_bool("use_shadowing_function", !sms_form);
        if (type == "normalmap") {
            auto normals = p.named_child<const Texture>("normalmap");
            if (!normals && p.has("filename")) normals = sms_normal_map(p);
            if (!normals)
                p.raise(
                    "normalmap needs a nested <texture name=\"normalmap\"> (a raw bitmap, usually) or, as in the "
                    "SMS code, a 'filename'");
            return std::make_shared<NormalMapBSDF>(normals, kids[0], opt);
        }
        // Mitsuba's bumpmap takes its one nested texture whatever its name.
        auto heights = p.children<const Texture>();
        if (heights.size() != 1) p.raise("bumpmap needs exactly one nested texture (the height field)");
        const double scale = p.get_float("scale", 1.0);
        if (!std::isfinite(scale)) p.raise_param("scale", "scale must be finite");
        return std::make_shared<BumpMapBSDF>(heights[0], scale, kids[0], opt);
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
            "roughconductor, plastic, roughplastic, twosided, blendbsdf, mask, null, normalmap, bumpmap, principled, "
            "principledthin)");
}

}  // namespace

std::shared_ptr<BSDF> create_bsdf(const Props& props) {
    auto bsdf = build(props);
    props.check_unused();
    bsdf->set_id(props.id());
    return bsdf;
}

}  // namespace snell
