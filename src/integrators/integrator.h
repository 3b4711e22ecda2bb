#pragma once
#include <memory>
#include <string>

#include "core/object.h"
#include "core/sampler.h"
#include "core/vector.h"

namespace snell {

class Scene;
class Props;

/// A per-sample estimator of radiance (Tungsten's "tracer"); the renderer owns tiles and
/// threads. `li` must be thread-safe (const) and draw all randomness from `sampler`.
class Integrator : public Object {
public:
    /// Radiance arriving at the camera along `ray` at wavelength `lambda` (nm).
    virtual double li(const Ray& ray, const Scene& scene, Sampler& sampler, double lambda) const = 0;
    /// The scene-file name of this technique ("path", "nee", ...).
    virtual std::string name() const = 0;
};

/// Builds an integrator from its `type`; unknown types are a SceneError at props' location.
std::shared_ptr<Integrator> create_integrator(const Props& props);

}  // namespace snell
