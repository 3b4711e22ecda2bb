#pragma once
// Mitsuba's `mesh_attribute`: a texture read from the attribute `name` of the mesh it is looked
// up on ("vertex_color" interpolated over the triangle, "face_weight" constant per face), times
// `scale`. Three channels are a colour (upsampled as a reflectance, like an sRGB texel), one a
// scalar. What it can take is known only on a mesh, so its nominal range is [0, scale]; the
// loader checks that every shape using it has the attribute.
#include <string>

#include "texture/texture.h"

namespace snell {

class MeshAttributeTexture final : public Texture {
public:
    MeshAttributeTexture(std::string name, double scale) : m_name(std::move(name)), m_scale(scale) {}

    SampledSpectrum eval(const SurfaceInteraction& si, const SampledWavelengths& wl) const override;
    double eval_float(const SurfaceInteraction& si) const override;
    RGB eval_rgb(const SurfaceInteraction& si) const override;
    double mean() const override { return 0.5 * m_scale; }
    double min_value() const override { return 0; }
    double max_value() const override { return m_scale; }

    const std::string& attribute_name() const { return m_name; }

private:
    /// The attribute at si and its channel count (0 when the shape lacks it).
    int lookup(const SurfaceInteraction& si, double v[3]) const;

    std::string m_name;
    double m_scale;
};

}  // namespace snell
