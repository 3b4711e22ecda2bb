#include "render/mpi_team.h"

#ifndef SNELL_HAVE_MPI

namespace snell {
int start_mpi_if_launched(int& /*argc*/, char**& /*argv*/) { return 0; }
void finish_mpi() {}
RenderTeam* mpi_team() { return nullptr; }
bool built_with_mpi() { return false; }
}  // namespace snell

#else

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace snell {

namespace {

constexpr int kTagRequest = 1, kTagGrant = 2;

/// One pixel of a film as the reduction moves it: exact sums, count, largest sample.
struct PixelRecord {
    uint64_t sum[9];
    uint64_t count;
    double largest[3];
    int64_t technique;
};

PixelRecord pack(const Film& f, int x, int y) {
    PixelRecord r{};
    const ExactSum3& s = f.exact_sum(x, y);
    const ExactSum* c[3] = {&s.x, &s.y, &s.z};
    for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) r.sum[3 * k + l] = c[k]->limbs()[size_t(l)];
    r.count = f.samples(x, y);
    const Vec3 m = f.largest_sample_xyz(x, y);
    r.largest[0] = m.x;
    r.largest[1] = m.y;
    r.largest[2] = m.z;
    r.technique = f.largest_sample_technique(x, y);
    return r;
}

ExactSum3 sums_of(const uint64_t* l) {
    ExactSum3 s;
    s.x = ExactSum::from_limbs({l[0], l[1], l[2]});
    s.y = ExactSum::from_limbs({l[3], l[4], l[5]});
    s.z = ExactSum::from_limbs({l[6], l[7], l[8]});
    return s;
}

void put_sums(const ExactSum3& s, uint64_t* l) {
    const ExactSum* c[3] = {&s.x, &s.y, &s.z};
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j) l[3 * k + j] = c[k]->limbs()[size_t(j)];
}

// The reduction's operators: exact sums add, the largest sample is the larger by
// PixelSamples' total order. Both are associative and commutative, so MPI may reduce in any
// tree and the result is the same bits.
void merge_pixels(void* in, void* inout, int* len, MPI_Datatype*) {
    const auto* a = static_cast<const PixelRecord*>(in);
    auto* b = static_cast<PixelRecord*>(inout);
    for (int i = 0; i < *len; ++i) {
        ExactSum3 s = sums_of(b[i].sum);
        s += sums_of(a[i].sum);
        put_sums(s, b[i].sum);
        b[i].count += a[i].count;
        PixelSamples cur{{}, 0, Vec3(b[i].largest[0], b[i].largest[1], b[i].largest[2]), int(b[i].technique)};
        const Vec3 other(a[i].largest[0], a[i].largest[1], a[i].largest[2]);
        if (cur.ranks_above_largest(other, int(a[i].technique))) {
            std::memcpy(b[i].largest, a[i].largest, sizeof(b[i].largest));
            b[i].technique = a[i].technique;
        }
    }
}

void merge_sums(void* in, void* inout, int* len, MPI_Datatype*) {
    const auto* a = static_cast<const uint64_t*>(in);
    auto* b = static_cast<uint64_t*>(inout);
    for (int i = 0; i < *len; ++i) {
        ExactSum3 s = sums_of(b + 9 * i);
        s += sums_of(a + 9 * i);
        put_sums(s, b + 9 * i);
    }
}

class MpiTeam final : public RenderTeam {
public:
    MpiTeam() {
        MPI_Comm_dup(MPI_COMM_WORLD, &m_comm);
        MPI_Comm_rank(m_comm, &m_rank);
        MPI_Comm_size(m_comm, &m_size);
        MPI_Type_contiguous(int(sizeof(PixelRecord)), MPI_BYTE, &m_pixel_type);
        MPI_Type_commit(&m_pixel_type);
        MPI_Type_contiguous(int(9 * sizeof(uint64_t)), MPI_BYTE, &m_sums_type);
        MPI_Type_commit(&m_sums_type);
        MPI_Op_create(&merge_pixels, 1, &m_pixel_op);
        MPI_Op_create(&merge_sums, 1, &m_sums_op);
    }
    ~MpiTeam() override {
        MPI_Op_free(&m_pixel_op);
        MPI_Op_free(&m_sums_op);
        MPI_Type_free(&m_pixel_type);
        MPI_Type_free(&m_sums_type);
        MPI_Comm_free(&m_comm);
    }
    int rank() const override { return m_rank; }
    int size() const override { return m_size; }

    void begin_pass(int64_t tiles, int threads, std::function<bool()> stop_requested) override {
        m_tiles = tiles;
        m_threads = std::max(1, threads);
        m_granted_next = m_granted_end = 0;
        m_stop = std::move(stop_requested);
        m_next = 0;
        m_cut = false;
        m_exhausted = false;
        m_stop_seen = false;
        if (m_rank == 0 && m_size > 1) m_dispatcher = std::thread([this] { dispatch(); });
    }

    WorkGrant next_tile() override {
        if (m_rank == 0) return take(false, 1).tile;
        // A worker rank asks rank 0, one request at a time (MPI_THREAD_SERIALIZED use), for a
        // run of tiles that its threads then take one by one (guided self-scheduling, below).
        std::lock_guard lock(m_ask);
        if (m_granted_next < m_granted_end && !m_force_stop) return {m_granted_next++, false};
        if (m_exhausted) return {-1, m_stop_seen};
        int64_t msg[2] = {m_force_stop || (m_stop && m_stop()) ? 1 : 0, m_threads};
        MPI_Send(msg, 2, MPI_INT64_T, 0, kTagRequest, m_comm);
        MPI_Recv(msg, 2, MPI_INT64_T, 0, kTagGrant, m_comm, MPI_STATUS_IGNORE);
        if (msg[0] < 0) {
            m_exhausted = true;
            m_stop_seen = msg[1] != 0;
            return {-1, m_stop_seen};
        }
        m_granted_next = msg[0] + 1;
        m_granted_end = msg[0] + msg[1];
        return {msg[0], false};
    }

    WorkGrant end_pass(bool* complete) override {
        const double t0 = MPI_Wtime();
        // A worker rank whose threads stopped asking (Ctrl-C cut a tile short) still owes the
        // dispatcher its last request: it asks once more, as stopping, so nothing waits.
        if (m_rank != 0) {
            m_force_stop = true;  // tiles still granted to it were cut: the pass is incomplete
            while (next_tile().tile >= 0) {
            }
            m_force_stop = false;
            m_granted_next = m_granted_end = 0;
        }
        int64_t state[2] = {0, 0};
        if (m_rank == 0) {
            if (m_dispatcher.joinable()) m_dispatcher.join();
            const bool stop = m_remote_stop || (m_stop && m_stop());
            state[0] = !m_cut && m_next.load() >= m_tiles;
            state[1] = stop;
        }
        MPI_Bcast(state, 2, MPI_INT64_T, 0, m_comm);
        m_times.pass_end_seconds += MPI_Wtime() - t0;
        if (complete) *complete = state[0] != 0;
        return {-1, state[1] != 0};
    }

    void sum_exactly(std::vector<double>& values) override {
        for (size_t off = 0; off < values.size(); off += size_t(INT_MAX / 2)) {
            const int n = int(std::min(values.size() - off, size_t(INT_MAX / 2)));
            MPI_Allreduce(MPI_IN_PLACE, values.data() + off, n, MPI_DOUBLE, MPI_SUM, m_comm);
        }
    }

    bool any(bool local) override {
        // The ends of the pilot's passes meet here: their wait is counted with end_pass's.
        const double t0 = MPI_Wtime();
        int v = local ? 1 : 0;
        MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_INT, MPI_LOR, m_comm);
        m_times.pass_end_seconds += MPI_Wtime() - t0;
        return v != 0;
    }

    void reduce(Film& film, StatTotals& stats) override {
        const double t0 = MPI_Wtime();
        const int w = film.width(), h = film.height();
        const size_t n = size_t(w) * size_t(h);
        // Pixels, in rows of at most INT_MAX records.
        std::vector<PixelRecord> buf(n), out(m_rank == 0 ? n : 0);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) buf[size_t(y) * w + x] = pack(film, x, y);
        reduce_chunks(buf.data(), m_rank == 0 ? out.data() : nullptr, n, sizeof(PixelRecord), m_pixel_type, m_pixel_op);
        uint64_t bytes = n * sizeof(PixelRecord);
        if (m_rank == 0)
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const PixelRecord& r = out[size_t(y) * w + x];
                    film.set_pixel(x, y, sums_of(r.sum), r.count, Vec3(r.largest[0], r.largest[1], r.largest[2]),
                                   int(r.technique));
                }
        // Splat layers: those any rank holds.
        int layers = film.splat_layers();
        MPI_Allreduce(MPI_IN_PLACE, &layers, 1, MPI_INT, MPI_MAX, m_comm);
        for (int layer = 0; layer < layers; ++layer) {
            if (!any(film.has_splats(layer))) continue;
            std::vector<uint64_t> s(9 * n, 0), sum(m_rank == 0 ? 9 * n : 0);
            if (film.has_splats(layer))
                for (size_t i = 0; i < n; ++i)
                    put_sums(film.exact_splat(layer, int(i % size_t(w)), int(i / size_t(w))), s.data() + 9 * i);
            reduce_chunks(s.data(), m_rank == 0 ? sum.data() : nullptr, n, 9 * sizeof(uint64_t), m_sums_type,
                          m_sums_op);
            bytes += n * 9 * sizeof(uint64_t);
            if (m_rank == 0)
                for (size_t i = 0; i < n; ++i)
                    film.set_splat(layer, int(i % size_t(w)), int(i / size_t(w)), sums_of(sum.data() + 9 * i));
        }
        // Statistics: every rank's slots, added on rank 0 in rank order.
        uint64_t slots = stats.slots().size();
        MPI_Allreduce(MPI_IN_PLACE, &slots, 1, MPI_UINT64_T, MPI_MAX, m_comm);
        std::vector<uint64_t> mine(slots, 0), all(m_rank == 0 ? slots * size_t(m_size) : 0);
        std::copy(stats.slots().begin(), stats.slots().end(), mine.begin());
        MPI_Gather(mine.data(), int(slots), MPI_UINT64_T, all.data(), int(slots), MPI_UINT64_T, 0, m_comm);
        if (m_rank == 0) {
            StatTotals total = StatTotals::from_slots(std::vector<uint64_t>(all.begin(), all.begin() + long(slots)));
            for (int r = 1; r < m_size; ++r)
                total += StatTotals::from_slots(
                    std::vector<uint64_t>(all.begin() + long(slots) * r, all.begin() + long(slots) * (r + 1)));
            stats = total;
        }
        bytes += slots * sizeof(uint64_t);
        // The account of the job's time (TeamTimes): every rank's wait at the ends of passes.
        double idle = m_times.pass_end_seconds;
        MPI_Reduce(m_rank == 0 ? MPI_IN_PLACE : &idle, &idle, 1, MPI_DOUBLE, MPI_SUM, 0, m_comm);
        m_times.idle_seconds = idle;
        m_times.reduce_bytes = bytes;
        m_times.reduce_seconds = MPI_Wtime() - t0;
        m_times.ranks = m_size;
        m_last = m_times;  // one render's account; the next render starts from zero
        m_times = {};
    }

    TeamTimes times() const override { return m_last; }

    [[noreturn]] void fail(const std::string& message, int exit_code) override {
        std::fprintf(stderr, "snell: error (rank %d of %d): %s\n", m_rank, m_size, message.c_str());
        std::fflush(stderr);
        MPI_Abort(MPI_COMM_WORLD, exit_code);
        std::exit(exit_code);
    }

private:
    // A run of tiles: the first, and how many.
    struct Run {
        WorkGrant tile;
        int64_t count = 0;
    };

    // Up to `want` tiles for rank 0's own threads (one) or for a worker rank's request.
    Run take(bool remote_stop, int64_t want) {
        if (remote_stop) m_remote_stop = true;
        if (m_remote_stop || (m_stop && m_stop())) {
            if (m_next.load() < m_tiles) m_cut = true;
            return {{-1, true}, 0};
        }
        const int64_t t = m_next.fetch_add(want);
        if (t >= m_tiles) return {};
        return {{t, false}, std::min(want, m_tiles - t)};
    }

    // Guided self-scheduling: a rank with `threads` threads is granted a share of what is left,
    // remaining / (4 N threads) tiles, at least 1 and at most one per thread. Early in a pass a
    // request serves all of a rank's threads (rank 0 answers up to `threads` times fewer), and
    // the last tiles go out one at a time, so the pass still ends within about one tile.
    int64_t grant_size(int64_t threads) const {
        const int64_t remaining = std::max<int64_t>(0, m_tiles - m_next.load());
        return std::clamp<int64_t>(remaining / (4 * int64_t(m_size) * std::max<int64_t>(1, threads)), 1,
                                   std::max<int64_t>(1, threads));
    }

    // Rank 0's dispatcher thread: answers requests until every worker rank was told that the
    // pass has no more work. The only thread of rank 0 that calls MPI during a pass.
    void dispatch() {
        int finished = 0;
        while (finished < m_size - 1) {
            int64_t msg[2];
            MPI_Status st;
            receive_request(msg, &st);
            const double t0 = MPI_Wtime();
            const Run r = take(msg[0] != 0, grant_size(msg[1]));
            const WorkGrant g = r.tile;
            int64_t reply[2] = {g.tile, g.tile >= 0 ? r.count : g.stop ? 1 : 0};
            MPI_Send(reply, 2, MPI_INT64_T, st.MPI_SOURCE, kTagGrant, m_comm);
            m_times.service_seconds += MPI_Wtime() - t0;
            ++m_times.requests;
            if (g.tile < 0) ++finished;
        }
    }

    // The next tile request. A blocking MPI_Recv busy-polls (Open MPI spins while it waits), and
    // the dispatcher shares its node with rank 0's render threads: it would take a core from
    // them whenever no request is pending (measured: 2 ranks x 1 thread on 2 cores took 102 s
    // against 83 s with this). So it tests for a request and sleeps between tests, 20 us at
    // first and twice as long each time up to 320 us: a request waits at most that (a tile
    // takes milliseconds), and under load requests are pending and the dispatcher never sleeps.
    void receive_request(int64_t* msg, MPI_Status* st) {
        MPI_Request req;
        MPI_Irecv(msg, 2, MPI_INT64_T, MPI_ANY_SOURCE, kTagRequest, m_comm, &req);
        int arrived = 0;
        int nap_us = 20;
        for (MPI_Test(&req, &arrived, st); !arrived; MPI_Test(&req, &arrived, st)) {
            std::this_thread::sleep_for(std::chrono::microseconds(nap_us));
            nap_us = std::min(320, 2 * nap_us);
        }
    }

    void reduce_chunks(void* send, void* recv, size_t count, size_t bytes, MPI_Datatype type, MPI_Op op) {
        const size_t chunk = size_t(1) << 24;
        for (size_t off = 0; off < count; off += chunk) {
            const int n = int(std::min(chunk, count - off));
            MPI_Reduce(static_cast<char*>(send) + off * bytes, recv ? static_cast<char*>(recv) + off * bytes : nullptr,
                       n, type, op, 0, m_comm);
        }
    }

    MPI_Comm m_comm{};
    int m_rank = 0, m_size = 1;
    MPI_Datatype m_pixel_type{}, m_sums_type{};
    MPI_Op m_pixel_op{}, m_sums_op{};
    int64_t m_tiles = 0;
    std::function<bool()> m_stop;
    std::atomic<int64_t> m_next{0};
    std::atomic<bool> m_cut{false}, m_remote_stop{false};
    std::thread m_dispatcher;
    std::mutex m_ask;
    bool m_exhausted = false, m_stop_seen = false, m_force_stop = false;
    int m_threads = 1;
    int64_t m_granted_next = 0, m_granted_end = 0;  // a worker rank's granted run of tiles
    TeamTimes m_times, m_last;
};

std::unique_ptr<MpiTeam>& the_team() {
    static std::unique_ptr<MpiTeam> team;
    return team;
}

/// Launched by an MPI launcher: Open MPI's mpirun, or a PMI/PMIx launcher such as Slurm's srun.
bool launched_by_mpi() {
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
        if (std::getenv(v)) return true;
    return false;
}

}  // namespace

int start_mpi_if_launched(int& argc, char**& argv) {
    if (!launched_by_mpi()) return 0;
    int provided = 0;
    if (MPI_Init_thread(&argc, &argv, MPI_THREAD_MULTIPLE, &provided) != MPI_SUCCESS) {
        std::fprintf(stderr, "snell: error: MPI did not start\n");
        return 1;
    }
    if (provided < MPI_THREAD_SERIALIZED) {
        std::fprintf(stderr, "snell: error: this MPI gives no thread support (MPI_THREAD_SERIALIZED needed)\n");
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    the_team() = std::make_unique<MpiTeam>();
    return 0;
}

void finish_mpi() {
    if (!the_team()) return;
    the_team().reset();
    MPI_Finalize();
}

RenderTeam* mpi_team() { return the_team().get(); }

bool built_with_mpi() { return true; }

}  // namespace snell

#endif
