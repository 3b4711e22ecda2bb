#pragma once
// Mitsuba's `checkerboard`: color0 where the fractional parts of u and v (after to_uv) are both
// below or both above 1/2, color1 elsewhere, so the unit uv square holds 2 x 2 cells.
#include "texture/texture.h"

namespace snell {

class CheckerboardTexture final : public Texture {
public:
    CheckerboardTexture(TextureRef color0, TextureRef color1, Transform to_uv)
        : m_color0(std::move(color0)), m_color1(std::move(color1)), m_to_uv(to_uv) {}

    SampledSpectrum eval(const SurfaceInteraction& si, const SampledWavelengths& wl) const override {
        return pick(si).eval(si, wl);
    }
    double eval_float(const SurfaceInteraction& si) const override { return pick(si).eval_float(si); }
    RGB eval_rgb(const SurfaceInteraction& si) const override { return pick(si).eval_rgb(si); }
    double mean() const override { return 0.5 * (m_color0->mean() + m_color1->mean()); }
    double min_value() const override { return std::min(m_color0->min_value(), m_color1->min_value()); }
    double max_value() const override { return std::max(m_color0->max_value(), m_color1->max_value()); }

    /// True where color0 applies.
    bool first_at(const Vec2& uv) const;

private:
    const Texture& pick(const SurfaceInteraction& si) const { return first_at(si.uv) ? *m_color0 : *m_color1; }

    TextureRef m_color0, m_color1;
    Transform m_to_uv;
};

}  // namespace snell
