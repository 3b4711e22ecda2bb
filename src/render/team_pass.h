#pragma once
// The work split every render loop shares (issue 27): how many threads, which team of processes,
// who draws the progress, how one pass of work items (tiles of the tile loop, Markov chains of
// PSSMLT) is handed out over the team's processes and each process's threads, and how a
// bootstrap (PSSMLT's normalisation, ERPT's deposition energy) is computed once over the team.
// Written once here, so that threads, MPI ranks, crops and sample ranges split every integrator
// the same way.
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/progress.h"
#include "render/render_team.h"

namespace snell {

struct RenderOptions;

/// The worker threads of this process: the options' count, or one per core it may run on.
int render_threads(const RenderOptions& opt);
/// The processes rendering together: the options' team, or process_team().
RenderTeam& render_team(const RenderOptions& opt);
/// The progress display of a render of `work` units (a time budget: the options' time), drawn by
/// rank 0 alone; null when the options ask for none or on the other ranks.
std::unique_ptr<ProgressBar> render_progress(const RenderOptions& opt, const RenderTeam& team, const std::string& label,
                                             uint64_t work);

/// When a render stops: Ctrl-C (`cancel`, may be null) or the options' time budget, counted from
/// construction (the render's start).
class RenderStop {
public:
    RenderStop(const RenderOptions& opt, const std::atomic<bool>* cancel);
    double elapsed() const;
    bool cancelled() const { return m_cancel && m_cancel->load(std::memory_order_relaxed); }
    /// Cancelled, or past the time budget: polled by the team at every work item.
    bool requested() const { return cancelled() || (m_limit > 0 && elapsed() >= m_limit); }

private:
    std::chrono::steady_clock::time_point m_start;
    double m_limit;
    const std::atomic<bool>* m_cancel;
};

/// How a pass ended, the same on every process.
struct PassOutcome {
    bool complete = true;  ///< every item was handed out and ran to its end
    bool stop = false;     ///< the render stops after this pass (time budget, Ctrl-C)
};

/// One pass over work items [0, items): the team hands each item to one thread of one process
/// (dynamically: caustic tiles cost many times the rest), and `work(item, slot)` renders it on
/// the thread with index `slot` < threads (slots own per-thread buffers); it returns false when
/// cut short (Ctrl-C). After every `group` items this process took, `between_groups()` runs on
/// the calling thread (merging splat buffers; SIZE_MAX: once, at the end). Called by every
/// process; `stop_requested` is polled where the team decides (rank 0).
PassOutcome run_team_pass(RenderTeam& team, tbb::task_arena& arena, int threads, int64_t items,
                          std::function<bool()> stop_requested, size_t group,
                          const std::function<bool(int64_t item, int slot)>& work,
                          const std::function<void()>& between_groups = {});

/// The values f(0) ... f(n-1) of a bootstrap, each computed once in the team (index i on rank
/// i mod N, on its threads) and summed exactly (every index is one process's), so that every
/// process holds all of them, bit for bit what one process computes.
std::vector<double> team_bootstrap(RenderTeam& team, tbb::task_arena& arena, size_t n,
                                   const std::function<double(size_t i)>& f);

}  // namespace snell
