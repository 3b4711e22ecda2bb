#pragma once
// A BSDF parameter that may vary over the surface (Mitsuba lets most of them be textures): a
// constant or a texture, read at the surface point the BSDFContext carries. Constructible from a
// plain Spectrum or double, so BSDFs built in code (tests, built-in scenes) stay one-liners.
#include <algorithm>

#include "bsdf/bsdf.h"
#include "bsdf/microfacet.h"
#include "texture/constant.h"

namespace snell {

class SpectrumParam {
public:
    SpectrumParam(const Spectrum& s) : m_const(s), m_tex(nullptr) {}  // NOLINT: implicit by design
    SpectrumParam(TextureRef t) : m_tex(std::move(t)) {               // NOLINT
        if (auto c = std::dynamic_pointer_cast<const ConstantTexture>(m_tex)) {
            m_const = c->spectrum();
            m_tex = nullptr;
        }
    }
    SampledSpectrum eval(const BSDFContext& ctx) const {
        return m_tex ? m_tex->eval(ctx.point(), ctx.wl) : m_const.eval(ctx.wl);
    }
    bool is_constant() const { return !m_tex; }
    /// Mean over wavelengths and the surface (Mitsuba's mean(), for lobe-selection weights).
    double average() const { return m_tex ? m_tex->mean() : m_const.average(); }
    /// The constant value (meaningful when is_constant()).
    const Spectrum& constant() const { return m_const; }

private:
    Spectrum m_const;
    TextureRef m_tex;
};

class FloatParam {
public:
    FloatParam(double v) : m_const(v) {}              // NOLINT: implicit by design
    FloatParam(TextureRef t) : m_tex(std::move(t)) {  // NOLINT
        if (m_tex && m_tex->is_constant()) {
            m_const = m_tex->mean();
            m_tex = nullptr;
        }
    }
    double eval(const BSDFContext& ctx) const { return m_tex ? m_tex->eval_float(ctx.point()) : m_const; }
    bool is_constant() const { return !m_tex; }
    double constant() const { return m_const; }
    double max_value() const { return m_tex ? m_tex->max_value() : m_const; }

private:
    double m_const = 0;
    TextureRef m_tex;
};

/// A microfacet distribution whose roughness may be textured (Mitsuba's alpha, alpha_u, alpha_v
/// on roughconductor and roughdielectric). Textured values are clamped to >= kMinAlpha: below
/// that the rough models cannot be evaluated (a constant alpha that small builds the smooth BSDF).
class MicrofacetParam {
public:
    static constexpr double kMinAlpha = 1e-3;

    MicrofacetParam(const MicrofacetDistribution& d) : m_base(d) {}  // NOLINT: implicit by design
    /// `alpha_u`, `alpha_v` replace the base's alphas; nullptr keeps them.
    MicrofacetParam(const MicrofacetDistribution& d, TextureRef alpha_u, TextureRef alpha_v)
        : m_base(d), m_alpha_u(std::move(alpha_u)), m_alpha_v(std::move(alpha_v)) {
        if (m_alpha_u && m_alpha_u->is_constant()) m_alpha_u = nullptr;
        if (m_alpha_v && m_alpha_v->is_constant()) m_alpha_v = nullptr;
    }
    MicrofacetDistribution eval(const BSDFContext& ctx) const {
        if (!m_alpha_u && !m_alpha_v) return m_base;
        const double au = m_alpha_u ? std::max(kMinAlpha, m_alpha_u->eval_float(ctx.point())) : m_base.alpha_u();
        const double av = m_alpha_v ? std::max(kMinAlpha, m_alpha_v->eval_float(ctx.point())) : m_base.alpha_v();
        return MicrofacetDistribution(m_base.type(), au, av, m_base.sample_visible());
    }
    bool is_constant() const { return !m_alpha_u && !m_alpha_v; }
    /// The distribution with the constant alphas (the textured ones' values where untextured).
    const MicrofacetDistribution& base() const { return m_base; }

private:
    MicrofacetDistribution m_base;
    TextureRef m_alpha_u, m_alpha_v;
};

}  // namespace snell
