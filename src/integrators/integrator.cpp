#include "integrators/integrator.h"

namespace snell {

RenderResult TileIntegrator::render(const Scene& scene, const FilmSpec& film, const RenderOptions& options,
                                    const std::atomic<bool>* cancel) const {
    const std::unique_ptr<SampleTracer> tracer = prepare(scene, film, options);
    return render_tiles(scene, *tracer, spectral_samples(), film, options, cancel);
}

}  // namespace snell
