#pragma once
// The render loop the Metropolis integrators share (pssmlt, hslt): a fixed number of Markov
// chains handed out over the team's threads and processes, each splatting into its own film
// that is added to the image exactly when the chain ends, so that a fixed-length render is a
// pure function of the seed whatever the thread or process count; progress, Ctrl-C and the time
// budget; and the image's normalisation (b times the window's film area over the mutations).
// What a chain is (its state, its mutations, its bootstrap) stays with each integrator.
#include <tbb/task_arena.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "core/progress.h"
#include "render/renderer.h"
#include "render/team_pass.h"

namespace snell {

class Props;

/// The chain counts every Metropolis integrator reads (mutations_per_pixel, bootstrap_samples,
/// chains), range-checked as 64-bit integers before use (issue 12: the fuzzer's
/// bootstrap_samples of 2^31 allocated 16 GiB; chains were narrowed to int). `who` names the
/// integrator in the messages; bootstrap_samples must be at least `min_bootstrap`.
void parse_chain_counts(const Props& props, const char* who, int64_t min_bootstrap, int64_t* mutations_per_pixel,
                        int64_t* bootstrap_samples, int* chains);

class MetropolisLoop {
public:
    /// `chains` 0: 64 (run `threads` at a time, so that a fixed-length image does not depend on
    /// the machine; an equal-time render runs them in rounds).
    /// `mutations_per_pixel` 0: the options' spp. Resets the statistics (the bootstrap counts).
    /// Throws for a crop or a sample range: a chain roams the whole film.
    MetropolisLoop(const FilmSpec& film, const RenderOptions& options, const std::atomic<bool>* cancel, int chains,
                   int64_t mutations_per_pixel, const char* label);

    RenderTeam& team() const { return *m_team; }
    tbb::task_arena& arena() { return m_arena; }
    bool timed() const { return m_timed; }
    int chains() const { return m_chains; }

    /// Adds v at full-film raster position `raster` to a chain's film, with the pixel filter's
    /// weights.
    void deposit(std::vector<Vec3>& film, const Vec2& raster, const Vec3& v) const;
    /// Whether chain mutation m of a chain with `quota` mutations runs: every 1024 mutations it
    /// counts progress and reads the stop request.
    bool keep_going(uint64_t m, uint64_t quota) const;

    /// A chain's films for run_parts: the expected-value splats of its states, which carry the
    /// normalisation b, and the large steps' splats as independent samples, which do not.
    struct ChainFilms {
        std::vector<Vec3> metropolis, independent;
    };
    using PartsChain = std::function<uint64_t(int c, uint64_t quota, ChainFilms& films)>;
    /// run() with the splats in two parts: when every chain is done, `metropolis_scale(mutations)`
    /// (called on every process, with the team's mutation count; it may run a team bootstrap)
    /// gives the factor the Metropolis part is scaled by (a refined b over the b in the weights),
    /// and the image is the independent part plus the scaled Metropolis part (scale 1 when the
    /// render was interrupted).
    RenderResult run_parts(const PartsChain& chain, const std::function<double(uint64_t mutations)>& metropolis_scale);

    /// Runs every chain: `chain(c, quota, film)` runs chain c on a cleared film (calling
    /// keep_going before each mutation) and returns the mutations it made. An equal-time render
    /// calls it once per round for every chain, with the round's quota: a chain keeps its state
    /// between calls. The chains' deposits
    /// carry b (expected-value weights (1 - a) b / Y ...); the image is the splats times the
    /// film area of the window over the mutations.
    RenderResult run(const std::function<uint64_t(int c, uint64_t quota, std::vector<Vec3>& film)>& chain);
    /// The image when the bootstrap found no light: black.
    RenderResult black();

private:
    RenderResult finish(RenderResult result, double splat_scale, uint64_t mutations) const;

    const FilmSpec& m_spec;
    const RenderOptions& m_opt;
    RenderTeam* m_team;
    RenderStop m_stopping;
    bool m_timed;
    int m_threads, m_chains;
    uint64_t m_total;
    tbb::task_arena m_arena;
    const char* m_label;
    std::unique_ptr<ProgressBar> m_bar;
};

}  // namespace snell
