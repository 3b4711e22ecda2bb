#pragma once
// BDPT's connections: the unweighted contribution of joining a camera and a light subpath.
#include <vector>

#include "integrators/bdpt/vertex.h"

namespace snell::bdpt {

// Unweighted contribution of connecting light vertex y_{s-1} (s >= 1) with camera vertex z_{t-1}.
SampledSpectrum connect(const Scene& scene, const std::vector<Vertex>& cam, const std::vector<Vertex>& lig, int s,
                        int t, const SampledWavelengths& wl);

// Unweighted contribution of the light-tracing strategy t = 1: light vertex y_{s-1} (s >= 2)
// seen by the pinhole at raster position `raster`. W_e cos(theta) / d^2 stands for the camera's
// factor of the connection, as f |cos| / d^2 does for a surface.
SampledSpectrum connect_camera(const Scene& scene, const Vertex& z0, const Vertex& y, const SampledWavelengths& wl,
                               Vec2* raster);

}  // namespace snell::bdpt
