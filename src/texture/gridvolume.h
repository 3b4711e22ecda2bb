#pragma once
// Mitsuba's `gridvolume` read as a texture (its `volume` texture): a 3D grid from a .vol file
// occupying the unit cube of its `to_world` (or, with use_grid_bbox, the box the file gives),
// looked up at the surface point, trilinear or nearest, with wrap mode clamp (default), repeat
// or mirror. One channel is a scalar; three a colour, upsampled per voxel as Mitsuba does
// (coefficients of rgb / (2 max), times 2 max: any brightness) and interpolated as spectra.
#include <memory>

#include "core/transform.h"
#include "io/volume_grid.h"
#include "texture/texture.h"

namespace snell {

class GridVolumeTexture final : public Texture {
public:
    GridVolumeTexture(VolumeGrid grid, Transform to_world, bool nearest, WrapMode wrap, bool raw);

    SampledSpectrum eval(const SurfaceInteraction& si, const SampledWavelengths& wl) const override;
    double eval_float(const SurfaceInteraction& si) const override;
    RGB eval_rgb(const SurfaceInteraction& si) const override;
    double mean() const override { return m_mean; }
    double min_value() const override { return m_min; }
    double max_value() const override { return m_max; }

private:
    /// The (up to 8) voxels and weights of a lookup at world point p.
    struct Footprint {
        int count = 0;
        size_t voxel[8];
        double w[8];
    };
    Footprint footprint(const Vec3& p) const;

    VolumeGrid m_grid;
    Transform m_to_local;
    bool m_nearest;
    WrapMode m_wrap;
    bool m_raw;
    std::vector<float> m_coeffs;              ///< per voxel: 3 sigmoid coefficients and a scale (colour grids)
    double m_mean = 0, m_min = 0, m_max = 0;  ///< of the scalar value (luminance for colours)
};

}  // namespace snell
