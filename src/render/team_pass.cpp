#include "render/team_pass.h"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <utility>

#include "render/renderer.h"

namespace snell {

int render_threads(const RenderOptions& opt) {
    // TBB's default honours the process's affinity mask: a rank that mpirun bound to one core
    // (Open MPI's default for small jobs) runs one thread, not one per core of the node.
    return opt.threads > 0 ? opt.threads : std::max(1, tbb::info::default_concurrency());
}

RenderTeam& render_team(const RenderOptions& opt) { return opt.team ? *opt.team : process_team(); }

std::unique_ptr<ProgressBar> render_progress(const RenderOptions& opt, const RenderTeam& team, const std::string& label,
                                             uint64_t work) {
    if (!(opt.progress || opt.progress_lines || opt.progress_fraction) || team.rank() != 0) return nullptr;
    std::unique_ptr<ProgressBar> bar(opt.time_limit > 0 ? new ProgressBar(ProgressBar::for_time(label, opt.time_limit))
                                                        : new ProgressBar(label, std::max<uint64_t>(1, work)));
    if (!opt.progress) bar->set_enabled(false);  // asked for lines or for the fraction alone
    if (opt.progress_lines) bar->set_lines(true);
    bar->set_fraction_sink(opt.progress_fraction);
    return bar;
}

RenderStop::RenderStop(const RenderOptions& opt, const std::atomic<bool>* cancel)
    : m_start(std::chrono::steady_clock::now()), m_limit(opt.time_limit), m_cancel(cancel) {}

double RenderStop::elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
}

PassOutcome run_team_pass(RenderTeam& team, tbb::task_arena& arena, int threads, int64_t items,
                          std::function<bool()> stop_requested, size_t group,
                          const std::function<bool(int64_t, int)>& work, const std::function<void()>& between_groups) {
    team.begin_pass(items, threads, std::move(stop_requested));
    std::atomic<bool> cut{false};
    bool exhausted = false;
    while (!exhausted && !cut) {
        // A group of items at a time, each thread asking the team for its next one.
        std::atomic<size_t> taken{0};
        std::atomic<bool> pass_over{false};
        arena.execute([&] {
            tbb::parallel_for(0, threads, [&](int slot) {
                while (taken.fetch_add(1) < group) {
                    const WorkGrant g = team.next_tile();
                    if (g.tile < 0) {
                        pass_over = true;
                        return;
                    }
                    if (!work(g.tile, slot)) {
                        cut = true;
                        return;
                    }
                }
            });
        });
        if (between_groups) between_groups();
        exhausted = pass_over;
    }
    bool handed_out_all = false;
    PassOutcome o;
    o.stop = team.end_pass(&handed_out_all).stop;
    o.complete = handed_out_all && !team.any(cut);
    return o;
}

std::vector<double> team_bootstrap(RenderTeam& team, tbb::task_arena& arena, size_t n,
                                   const std::function<double(size_t)>& f) {
    std::vector<double> v(n, 0.0);
    const size_t ranks = size_t(team.size()), rank = size_t(team.rank());
    const size_t mine = n > rank ? (n - rank + ranks - 1) / ranks : 0;  // indices rank, rank + N, ...
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, mine, 256), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t k = r.begin(); k < r.end(); ++k) v[rank + k * ranks] = f(rank + k * ranks);
        });
    });
    team.sum_exactly(v);  // each entry is one process's, zero elsewhere: exact
    return v;
}

}  // namespace snell
