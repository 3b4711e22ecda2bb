#include "integrators/mnee/mnee_integrator.h"

#include <cmath>

#include "core/props.h"
#include "integrators/mnee/connection_allocation.h"
#include "integrators/mnee/mnee_path.h"
#include "manifold/walk_counters.h"
#include "manifold/work_meter.h"
#include "render/camera_sample.h"

namespace snell {

namespace {

/// The `mnee` integrator's per-render tracer. With a learned allocation, the first pilot_spp
/// samples of every pixel run at the pilot's q and record what ConnectionAllocation needs; after
/// the pass that completes them, every sample runs at its region's q. Without, every sample runs
/// at connect_probability.
class MneeTracer final : public SampleTracer {
public:
    MneeTracer(const MneeIntegrator& mnee, const FilmSpec& film) : m_mnee(mnee) {
        const MneeSettings& st = mnee.mnee_settings();
        if (!st.learned_allocation) return;
        m_pilot_spp = uint64_t(st.pilot_spp);
        // Regions may do without the surface trials only where their solutions are weighed apart.
        m_allocation = std::make_unique<ConnectionAllocation>(
            film.out_width(), film.out_height(), film.crop_x, film.crop_y, st.allocation_block, st.connect_probability,
            st.splits_surface_solutions() ? st.trial_allocation : TrialAllocation::Always, st.work_price,
            st.splits_surface_solutions() && st.failed_walk_trials && !(st.failed_walk_weight > 0));
    }

    SampleEstimate li_splat(const CameraSample& cs, const Ray& ray, const Scene& scene, Sampler& sampler,
                            SplatList& /*splats*/) const override {
        if (!m_allocation) return path(scene, cs, ray, -1, nullptr, true).trace(sampler);
        const int x = int(std::floor(cs.pixel_centre.x)), y = int(std::floor(cs.pixel_centre.y));
        const double q = m_allocation->q(x, y);
        const bool trials = m_allocation->surface_trials(x, y);
        if (!m_allocation->learning())
            return path(scene, cs, ray, q, nullptr, trials, m_allocation->failed_walk_trials(x, y)).trace(sampler);
        // A pilot sample: its pixel's statistics are written by the one thread rendering it.
        PilotSample record;
        const double w0 = work_so_far();
        const SampleEstimate e = path(scene, cs, ray, q, &record, trials).trace(sampler);
        m_allocation->add(x, y, record, e.L.average(), work_so_far() - w0);
        return e;
    }
    void end_pass(uint64_t samples_per_pixel) override {
        if (!m_allocation || !m_allocation->learning() || samples_per_pixel < m_pilot_spp) return;
        m_allocation->fit();
        const auto h = m_allocation->histogram();
        for (size_t j = 0; j < h.size(); ++j) walk_counters::allocation_regions.add(int64_t(j), h[j]);
        walk_counters::allocation_regions_without_trials += m_allocation->regions_without_trials();
        walk_counters::allocation_regions_failed_walk_trials += m_allocation->regions_with_failed_walk_trials();
    }
    bool learning() const override { return m_allocation && m_allocation->learning(); }
    uint64_t pilot_samples() const override { return m_allocation ? m_pilot_spp : 0; }
    void pilot_window(int& x0, int& y0, int& x1, int& y1) const override {
        if (m_allocation) m_allocation->widen_to_regions(x0, y0, x1, y1);
    }
    std::vector<PixelRect> pilot_extra(const PixelRect& window) const override {
        std::vector<PixelRect> rects;
        if (m_allocation)
            for (const auto& r : m_allocation->lattice_outside(window.x0, window.y0, window.x1, window.y1))
                rects.push_back({r[0], r[1], r[2], r[3]});
        return rects;
    }
    std::vector<double> pilot_state() const override {
        return m_allocation ? m_allocation->pilot_state() : std::vector<double>{};
    }
    void set_pilot_state(const std::vector<double>& state) override {
        if (m_allocation) m_allocation->set_pilot_state(state);
    }
    double max_sample_share() const override { return m_mnee.settings().max_sample_share; }
    int clamp_spread() const override { return m_mnee.settings().clamp_spread; }
    std::vector<std::string> technique_names() const override { return path_technique_names(); }

private:
    MneePath path(const Scene& scene, const CameraSample& cs, const Ray& ray, double q, PilotSample* pilot, bool trials,
                  bool failed_walk_trials = false) const {
        return MneePath(scene, m_mnee.settings(), m_mnee.mnee_settings(), cs.wl, ray, nullptr, q, pilot, trials,
                        failed_walk_trials);
    }

    const MneeIntegrator& m_mnee;
    uint64_t m_pilot_spp = 0;
    std::unique_ptr<ConnectionAllocation> m_allocation;  ///< pointer: li_splat() is const; null: fixed q
};

}  // namespace

SampleEstimate MneeIntegrator::radiance(const Ray& ray, const Scene& scene, Sampler& sampler,
                                        const SampledWavelengths& wl, PathObserver* observer) const {
    return MneePath(scene, m_settings, m_mnee, wl, ray, observer, -1, nullptr).trace(sampler);
}

std::unique_ptr<SampleTracer> MneeIntegrator::prepare(const Scene& /*scene*/, const FilmSpec& film,
                                                      const RenderOptions& /*options*/) const {
    return std::make_unique<MneeTracer>(*this, film);
}

PathSettings MneeIntegrator::path_settings_from_props(const Props& p) {
    PathSettings s = PathSettings::tracer_from_props(p);
    if (p.get_bool("biased", false) && !p.has("max_sample_share")) s.max_sample_share = kBiasedMaxSampleShare;
    if (p.get_bool("biased", false) && !p.has("clamp_spread")) s.clamp_spread = kBiasedClampSpread;
    // The paper's estimator (solutions=one) keeps the paper's BSDF sampling.
    if (!p.has("caster_probability") && p.get_string("solutions", "") != "one")
        s.caster_probability = kMneeCasterProbability;
    return s;
}

}  // namespace snell
