#pragma once
// The processes that render one frame together (issue 27): one process alone (LocalTeam), or
// the ranks of an MPI job (MpiTeam, render/mpi_team.h). The render loop asks the team for its
// next piece of work and hands it the finished film; everything else (threads, passes, tiles)
// is the same whatever the team. Films add exactly (ExactSum), so a team may hand out work in any
// order and reduce films in any order and still give the image one process renders.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "camera/film.h"
#include "core/stats.h"
#include "render/pixel_rect.h"

namespace snell {

/// What the team says about the next tile of a pass.
struct WorkGrant {
    int64_t tile = -1;  ///< the tile to render; -1: the pass has no more work for this process
    bool stop = false;  ///< with tile -1: the render stops after this pass (time, Ctrl-C)
};

/// Where an MPI job's time went, for the scaling model (docs/distributed.md, "Scaling"): rank
/// 0's view after the reduction. All zero for one process.
struct TeamTimes {
    int ranks = 1;
    uint64_t requests = 0;        ///< tile requests rank 0's dispatcher answered
    double service_seconds = 0;   ///< its time spent answering them (receive to reply sent)
    double pass_end_seconds = 0;  ///< rank 0's wait at the ends of passes for the other ranks
    double idle_seconds = 0;      ///< the same wait summed over every rank
    double reduce_seconds = 0;    ///< the final reduction of films and statistics (rank 0)
    uint64_t reduce_bytes = 0;    ///< bytes each rank contributed to it
};

class RenderTeam {
public:
    virtual ~RenderTeam() = default;
    virtual int rank() const = 0;
    virtual int size() const = 0;
    /// Starts a pass of `tiles` tiles for this process's `threads` worker threads;
    /// `stop_requested` is polled by whoever decides when the team stops (this process alone, or
    /// rank 0 of an MPI job): the time budget, Ctrl-C. Called by every process.
    virtual void begin_pass(int64_t tiles, int threads, std::function<bool()> stop_requested) = 0;
    /// The next tile of the current pass for the calling worker thread (any thread).
    virtual WorkGrant next_tile() = 0;
    /// Ends the pass (every process): true when every tile of it was handed out, and whether the
    /// render stops after it. Every process gets the same answer.
    virtual WorkGrant end_pass(bool* complete) = 0;
    /// Sums `values` over the processes, exactly where every process but one holds zeros
    /// (MNEE's pilot statistics); every process gets the sum.
    virtual void sum_exactly(std::vector<double>& values) = 0;
    /// True on every process when `local` is true on any.
    virtual bool any(bool local) = 0;
    /// Adds every process's film and statistics into rank 0's (the others' are left as they
    /// are). Exact: the result does not depend on the order.
    virtual void reduce(Film& film, StatTotals& stats) = 0;
    /// Rank 0's account of the job's time so far (TeamTimes).
    virtual TeamTimes times() const { return {}; }
    /// Reports a failure of this process and ends the job (MPI: every rank, non-zero exit).
    [[noreturn]] virtual void fail(const std::string& message, int exit_code) = 0;
};

/// One process: every tile is this process's, handed out in order to its threads.
class LocalTeam final : public RenderTeam {
public:
    int rank() const override { return 0; }
    int size() const override { return 1; }
    void begin_pass(int64_t tiles, int threads, std::function<bool()> stop_requested) override;
    WorkGrant next_tile() override;
    WorkGrant end_pass(bool* complete) override;
    void sum_exactly(std::vector<double>& /*values*/) override {}
    bool any(bool local) override { return local; }
    void reduce(Film& /*film*/, StatTotals& /*stats*/) override {}
    [[noreturn]] void fail(const std::string& message, int exit_code) override;

private:
    int64_t m_tiles = 0;
    std::function<bool()> m_stop;
    std::atomic<int64_t> m_next{0};
    std::atomic<bool> m_cut{false};
};

/// The team of this process: the MPI job's when snell runs under mpirun (and was built with
/// MPI), else a LocalTeam. Made once, on first use; render_tiles uses it unless told otherwise.
RenderTeam& process_team();

}  // namespace snell
