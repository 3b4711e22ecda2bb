#include "render/render_team.h"

#include <cstdio>
#include <cstdlib>
#include <utility>

#include "render/mpi_team.h"

namespace snell {

void LocalTeam::begin_pass(int64_t tiles, int /*threads*/, std::function<bool()> stop_requested) {
    m_tiles = tiles;
    m_stop = std::move(stop_requested);
    m_next = 0;
    m_cut = false;
}

WorkGrant LocalTeam::next_tile() {
    if (m_stop && m_stop()) {
        if (m_next.load() < m_tiles) m_cut = true;
        return {-1, true};
    }
    const int64_t t = m_next.fetch_add(1);
    if (t >= m_tiles) return {};
    return {t, false};
}

WorkGrant LocalTeam::end_pass(bool* complete) {
    if (complete) *complete = !m_cut && m_next.load() >= m_tiles;
    return {-1, m_stop && m_stop()};
}

void LocalTeam::fail(const std::string& message, int exit_code) {
    std::fprintf(stderr, "snell: error: %s\n", message.c_str());
    std::exit(exit_code);
}

RenderTeam& process_team() {
    if (RenderTeam* mpi = mpi_team()) return *mpi;
    static LocalTeam local;
    return local;
}

}  // namespace snell
