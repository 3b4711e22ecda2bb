// The outlier clamp's spread (Film::set_max_sample_share with spread_radius; issue 10, mnee's
// biased mode). The clamp alone drops the light it takes. Where a pixel's light comes from rare
// bright samples (a caustic's dim halo at a few samples per pixel: one sample in sixteen lands
// there), it takes nearly all of it: no per-pixel rule can tell that sample from a firefly. The
// neighbourhood can: spread over a disc, the pieces of many such samples add up to a smooth
// image in which none dominates. Energy is kept exactly; the bias is a blur of the clamped
// light over at most spread_radius pixels, and like the clamp it fades as samples grow.
#include <cmath>

#include "camera/film.h"

namespace snell {

namespace {

/// A disc's offsets, nearest rings first: disc r is the first end[r] of them, the pixels with
/// dx² + dy² <= r² + r (which rounds the disc out to the 3x3 square at r = 1).
struct DiscOffsets {
    std::vector<std::pair<int, int>> d;
    std::vector<size_t> end;
    explicit DiscOffsets(int radius) : end(size_t(radius) + 1) {
        for (int r = 0; r <= radius; ++r) {
            for (int dy = -r; dy <= r; ++dy)
                for (int dx = -r; dx <= r; ++dx) {
                    const int q = dx * dx + dy * dy;
                    if (q <= r * r + r && (r == 0 || q > (r - 1) * (r - 1) + (r - 1))) d.emplace_back(dx, dy);
                }
            end[size_t(r)] = d.size();
        }
    }
};

/// A source's disc starts as the smallest that holds this many times the source's light from
/// elsewhere (the pixels' own light and other sources'), so that each of its pixels receives,
/// on average, pieces and light worth twice its piece: few are left dominated for the rounds
/// below to mend, and sources in a sparse halo start wide enough to overlap.
constexpr double kLightAround = 2.0;

}  // namespace

void Film::spread_clamped_light() {
    m_spread.clear();
    m_piece_y.clear();
    m_spread_r.clear();
    if (!(m_max_share > 0) || m_spread_radius <= 0) return;
    const int radius_cap = std::min(m_spread_radius, 255);
    const size_t n = m_xyz.size();

    // The sources: pixels whose largest sample the clamp scaled down, with the light it took
    // (as a mean over the pixel's samples: the pixel's value falls by as much).
    struct Source {
        int x, y;
        Vec3 light;
        int r = 1;
        bool dropped = false;
    };
    std::vector<Source> sources;
    std::vector<double> own_y(n, 0.0);  // each pixel's mean luminance after the clamp
    for (int y = 0; y < m_h; ++y)
        for (int x = 0; x < m_w; ++x) {
            const size_t i = size_t(y) * m_w + x;
            if (!m_n[i]) continue;
            const double c = clamped_y(x, y);
            own_y[i] = (m_xyz[i].y - c) / double(m_n[i]);
            if (c > 0) sources.push_back({x, y, m_max_xyz[i] * (c / m_max_y[i] / double(m_n[i]))});
        }
    if (sources.empty()) return;
    const DiscOffsets disc(radius_cap);
    const auto for_disc = [&](const Source& s, int r, auto&& f) {
        for (size_t k = 0; k < disc.end[size_t(r)]; ++k) {
            const int x = s.x + disc.d[k].first, y = s.y + disc.d[k].second;
            if (x < 0 || y < 0 || x >= m_w || y >= m_h) continue;
            // Pixels that received samples only: the image's edge and unrendered pixels lose nothing.
            if (const size_t i = size_t(y) * m_w + x; m_n[i] > 0) f(i);
        }
    };

    // Starting discs (kLightAround).
    std::vector<double> light_y(n, 0.0);
    for (const Source& s : sources) light_y[size_t(s.y) * m_w + s.x] = s.light.y;
    for (Source& s : sources) {
        double around = -s.light.y;
        size_t k = 0;
        for (s.r = 1; s.r < radius_cap; ++s.r) {
            for (; k < disc.end[size_t(s.r)]; ++k) {
                const int x = s.x + disc.d[k].first, y = s.y + disc.d[k].second;
                if (x < 0 || y < 0 || x >= m_w || y >= m_h) continue;
                const size_t i = size_t(y) * m_w + x;
                around += own_y[i] + light_y[i];
            }
            if (around >= kLightAround * s.light.y) break;
        }
    }

    m_spread.assign(n, Vec3());
    m_piece_y.assign(n, 0.0);
    std::vector<int64_t> piece_src(n, -1);  // the source of each pixel's largest piece
    std::vector<uint8_t> act(sources.size());
    // Each round spreads every source evenly over its disc, then widens the disc of each source
    // whose piece still carries more than the share allowed of some pixel. A source that still
    // does so at radius_cap is a firefly with too little light around it to hide in (its light
    // would show as a faint disc of its own): its light is dropped, as by the clamp alone, and
    // the next round checks the pixels it lit. Discs only grow and sources are only dropped, so
    // the rounds end.
    for (;;) {
        std::fill(m_spread.begin(), m_spread.end(), Vec3());
        std::fill(m_piece_y.begin(), m_piece_y.end(), 0.0);
        std::fill(piece_src.begin(), piece_src.end(), -1);
        for (size_t k = 0; k < sources.size(); ++k) {
            const Source& s = sources[k];
            if (s.dropped) continue;
            int count = 0;
            for_disc(s, s.r, [&](size_t) { ++count; });
            const Vec3 piece = s.light / double(count);  // count >= 1: the source itself
            for_disc(s, s.r, [&](size_t i) {
                m_spread[i] += piece;
                if (piece.y > m_piece_y[i]) {
                    m_piece_y[i] = piece.y;
                    piece_src[i] = int64_t(k);
                }
            });
        }
        std::fill(act.begin(), act.end(), 0);
        bool any = false;
        for (size_t i = 0; i < n; ++i)
            if (piece_src[i] >= 0 && m_piece_y[i] > m_max_share * (own_y[i] + m_spread[i].y))
                act[size_t(piece_src[i])] = any = true;
        if (!any) break;
        for (size_t k = 0; k < sources.size(); ++k)
            if (act[k]) {
                if (sources[k].r < radius_cap)
                    ++sources[k].r;
                else
                    sources[k].dropped = true;
            }
    }
    m_spread_r.assign(n, 0);
    for (const Source& s : sources)
        if (!s.dropped) m_spread_r[size_t(s.y) * m_w + s.x] = uint8_t(s.r);
}

}  // namespace snell
