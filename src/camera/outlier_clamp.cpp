// The outlier clamp of mnee's biased mode (issue 10) as a post-process of a finished film
// (issue 27): it runs once, after the last sample, after the reduction over MPI ranks or the
// merge of partial films, and reads only what the film accumulated, so that a distributed image
// equals the local one.
//
// The clamp alone drops the light it takes. Where a pixel's light comes from rare bright samples
// (a caustic's dim halo at a few samples per pixel: one sample in sixteen lands there), it takes
// nearly all of it: no per-pixel rule can tell that sample from a firefly. The neighbourhood can:
// spread over a disc, the pieces of many such samples add up to a smooth image in which none
// dominates. Energy is kept exactly; the bias is a blur of the clamped light over at most
// spread_radius pixels, and like the clamp it fades as samples grow.
#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include "camera/outlier_clamp.h"

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

namespace {

// The spread of the light the clamp (out.max_share) takes from `film`'s pixels over discs of
// at most out.spread_radius pixels, into out's spread fields.
void spread_clamped_light(const Film& film, OutlierClamp& out) {
    const double share = out.max_share;
    const int w = film.width(), h = film.height();
    const int radius_cap = std::min(out.spread_radius, 255);
    const size_t n = size_t(w) * size_t(h);
    std::vector<uint64_t> counts(n);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) counts[size_t(y) * w + x] = film.samples(x, y);
    std::vector<Vec3>& added = out.spread;
    std::vector<double>& largest_piece_y = out.piece_y;

    // The sources: pixels whose largest sample the clamp scaled down, with the light it took
    // (as a mean over the pixel's samples: the pixel's value falls by as much).
    struct Source {
        int x, y;
        Vec3 light;
        int r = 1;
        bool lit_only = false;  // spread over lit pixels only (see the rounds below)
        bool stuck = false;     // at its widest: moves no more
    };
    std::vector<Source> sources;
    std::vector<double> own_y(n, 0.0);  // each pixel's mean luminance after the clamp
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            if (!counts[i]) continue;
            const double c = film.clamped_y(x, y);
            own_y[i] = (film.sample_sum_y(x, y) - c) / double(counts[i]);
            if (c > 0)
                sources.push_back(
                    {x, y, film.largest_sample_xyz(x, y) * (c / film.largest_sample_y(x, y) / double(counts[i]))});
        }
    if (sources.empty()) return;
    std::vector<double> light_y(n, 0.0);  // each source pixel's clamped light
    for (const Source& s : sources) light_y[size_t(s.y) * w + s.x] = s.light.y;
    const DiscOffsets disc(radius_cap);
    // Whether pixel i can take a piece of source s: pixels that received samples only (so the
    // image's edge and unrendered pixels lose nothing), and lit ones only once s is lit_only.
    const auto receives = [&](const Source& s, size_t i) {
        return counts[i] > 0 && (!s.lit_only || own_y[i] > 0 || light_y[i] > 0);
    };
    const auto for_disc = [&](const Source& s, auto&& f) {
        for (size_t k = 0; k < disc.end[size_t(s.r)]; ++k) {
            const int x = s.x + disc.d[k].first, y = s.y + disc.d[k].second;
            if (x < 0 || y < 0 || x >= w || y >= h) continue;
            if (const size_t i = size_t(y) * w + x; receives(s, i)) f(i);
        }
    };

    // Starting discs (kLightAround).
    for (Source& s : sources) {
        double around = -s.light.y;
        size_t k = 0;
        for (s.r = 1; s.r < radius_cap; ++s.r) {
            for (; k < disc.end[size_t(s.r)]; ++k) {
                const int x = s.x + disc.d[k].first, y = s.y + disc.d[k].second;
                if (x < 0 || y < 0 || x >= w || y >= h) continue;
                const size_t i = size_t(y) * w + x;
                around += own_y[i] + light_y[i];
            }
            if (around >= kLightAround * s.light.y) break;
        }
    }

    // Each source spreads its light evenly over its disc's pixels (its support). Rounds then
    // widen, together, the discs of the sources whose piece still carries more than the share
    // allowed of some pixel (together, so that neighbouring discs grow into each other's gaps).
    // A source that still does so at radius_cap usually has black pixels in its disc (a firefly
    // beside a shadow), where any piece is all of the pixel: it starts again from radius 1 over
    // lit pixels only (pixels with light of their own or clamped light), which keeps the black
    // ones black. One that dominates even so, at radius_cap, stays as it is. Each source only
    // moves forward (wider, then lit only, then stuck), so the rounds end. Last, a pixel that a
    // stuck source's piece still dominates keeps of each piece only as much as lets none
    // dominate it (below): that light is dropped, as by the clamp alone, but only there. (Dropping
    // the whole source instead would take light from the pixels around it, leave other sources
    // dominating there, and where clamped light is sparse and uneven, a heavy tail on black, run
    // on from source to source.)
    std::vector<double> piece_y(sources.size());  // each source's piece (luminance)
    std::vector<int64_t> source_at(n, -1);
    for (size_t k = 0; k < sources.size(); ++k) source_at[size_t(sources[k].y) * w + sources[k].x] = int64_t(k);
    // Adds (sign 1) or removes (-1) source k's pieces; `touched` collects its support.
    const auto spread = [&](size_t k, double sign, std::vector<size_t>* touched) {
        const Source& s = sources[k];
        int count = 0;
        for_disc(s, [&](size_t) { ++count; });
        const Vec3 piece = s.light / double(count);  // count >= 1: the source itself
        piece_y[k] = piece.y;
        for_disc(s, [&](size_t i) {
            added[i] += piece * sign;
            if (touched) touched->push_back(i);
        });
    };
    // Calls f(k) for every source k whose support holds pixel i (sources within radius_cap).
    const auto for_sources_at = [&](size_t i, auto&& f) {
        const int x = int(i % size_t(w)), y = int(i / size_t(w));
        for (int v = std::max(0, y - radius_cap); v <= std::min(h - 1, y + radius_cap); ++v)
            for (int u = std::max(0, x - radius_cap); u <= std::min(w - 1, x + radius_cap); ++u) {
                const int64_t k = source_at[size_t(v) * w + u];
                if (k < 0) continue;
                const Source& s = sources[size_t(k)];
                if ((x - s.x) * (x - s.x) + (y - s.y) * (y - s.y) <= s.r * s.r + s.r && receives(s, i)) f(size_t(k));
            }
    };
    // The source whose piece is largest at pixel i (-1: none).
    const auto largest_piece = [&](size_t i) {
        int64_t best = -1;
        for_sources_at(i, [&](size_t k) {
            if (best < 0 || piece_y[k] > piece_y[size_t(best)]) best = int64_t(k);
        });
        return best;
    };

    added.assign(n, Vec3());
    largest_piece_y.assign(n, 0.0);
    std::vector<int64_t> best(n, -1);  // the source of each pixel's largest piece
    std::vector<uint8_t> acting(sources.size()), fresh(n);
    std::vector<size_t> round, next, touched;
    // A move lowers the light of the pixels the source leaves or thins, which can leave other
    // sources dominating there; where clamped light is sparse and uneven (a heavy tail on black)
    // this runs on from source to source for hundreds of rounds. After this many (a source
    // needs at most 2 radius_cap + 1 moves), sources that still dominate stay as they are, and
    // the cut below takes care of the pixels they dominate.
    const int max_rounds = 4 * radius_cap + 4;
    int rounds = 0;
    // Queues the source of pixel i's largest piece if that piece dominates the pixel.
    const auto check = [&](size_t i) {
        const int64_t k = best[i];
        if (k >= 0 && !acting[size_t(k)] && !sources[size_t(k)].stuck &&
            piece_y[size_t(k)] > share * (own_y[i] + added[i].y)) {
            acting[size_t(k)] = 1;
            next.push_back(size_t(k));
        }
    };
    for (;;) {
        // A full pass, exact (each pixel's light summed afresh), finds the sources whose pieces
        // dominate a pixel; the rounds then update the sums in place, each at the cost of the
        // sources it moves.
        std::fill(added.begin(), added.end(), Vec3());
        std::fill(best.begin(), best.end(), -1);
        for (size_t k = 0; k < sources.size(); ++k) spread(k, 1.0, nullptr);
        for (size_t k = 0; k < sources.size(); ++k)
            for_disc(sources[k], [&](size_t i) {
                if (best[i] < 0 || piece_y[k] > piece_y[size_t(best[i])]) best[i] = int64_t(k);
            });
        for (size_t i = 0; i < n; ++i) check(i);
        if (next.empty()) break;
        while (!next.empty()) {
            round.swap(next);
            next.clear();
            touched.clear();
            ++rounds;
            for (size_t k : round) {
                spread(k, -1.0, &touched);
                Source& src = sources[k];
                if (rounds > max_rounds) {
                    src.stuck = true;
                } else if (src.r < radius_cap) {
                    ++src.r;
                } else if (!src.lit_only) {
                    src.lit_only = true;
                    src.r = 1;
                } else {
                    src.stuck = true;
                }
            }
            for (size_t k : round) spread(k, 1.0, &touched);
            // Where a moved source was largest, the largest is found afresh; elsewhere it is the
            // old one or a moved source's new piece.
            for (size_t i : touched)
                if (!fresh[i] && best[i] >= 0 && acting[size_t(best[i])]) {
                    best[i] = largest_piece(i);
                    fresh[i] = 1;
                }
            for (size_t k : round)
                for_disc(sources[k], [&](size_t i) {
                    if (!fresh[i] && (best[i] < 0 || piece_y[k] > piece_y[size_t(best[i])])) best[i] = int64_t(k);
                });
            for (size_t k : round) acting[k] = 0;
            for (size_t i : touched) {
                fresh[i] = 0;
                check(i);
            }
        }
        // The sums now carry rounding; the full pass starts again from zero and checks every pixel
        // once more (it rarely finds anything left to do).
    }
    // Pixels a stuck source's piece dominates: each piece is cut to the largest level c at which
    // none dominates, c <= s (own + sum of min(piece, c)) (water-filling over the pieces, largest
    // first); the rest of those pieces is dropped.
    std::vector<std::pair<double, int64_t>> pieces;
    for (size_t i = 0; i < n; ++i) {
        largest_piece_y[i] = best[i] >= 0 ? piece_y[size_t(best[i])] : 0.0;
        if (!(largest_piece_y[i] > share * (own_y[i] + added[i].y))) continue;
        pieces.clear();
        for_sources_at(i, [&](size_t k) { pieces.emplace_back(piece_y[k], int64_t(k)); });
        std::sort(pieces.begin(), pieces.end(), std::greater<>());
        // On the segment where k pieces exceed c: c = s (A + k c), A = own + the smaller pieces.
        double below = own_y[i];
        for (const auto& p : pieces) below += p.first;
        double c = 0;
        for (size_t k = 0; k < pieces.size(); ++k) {
            below -= pieces[k].first;  // now own + the pieces after the k + 1 largest
            const double top = pieces[k].first, floor = k + 1 < pieces.size() ? pieces[k + 1].first : 0.0;
            const double g_top = share * (below + double(k + 1) * top) - top;
            if (g_top >= 0) {
                c = top;
                break;
            }
            if (share * double(k + 1) < 1) {
                const double at = share * below / (1 - share * double(k + 1));
                if (at >= floor) {
                    c = at * (1 - 1e-12);  // just below the equality, which rounding could tip over
                    break;
                }
            }
        }
        for (const auto& [py, k] : pieces) {
            if (!(py > c)) break;
            added[i] -= sources[size_t(k)].light * ((py - c) / sources[size_t(k)].light.y);
        }
        largest_piece_y[i] = std::min(largest_piece_y[i], c);
        ++out.cut_pixels;
    }
    out.radius.assign(n, 0);
    for (const Source& s : sources) {
        out.radius[size_t(s.y) * w + s.x] = uint8_t(s.r);
        out.taken_y += s.light.y;
    }
    for (size_t i = 0; i < n; ++i) out.given_y += added[i].y;
}

}  // namespace

void apply_outlier_clamp(Film& film, double max_share, int spread_radius) {
    OutlierClamp clamp;
    clamp.max_share = max_share;
    clamp.spread_radius = spread_radius;
    film.set_outlier_clamp(clamp);  // the per-pixel clamp first: the spread moves what it took
    if (!(max_share > 0) || spread_radius <= 0) return;
    spread_clamped_light(film, clamp);
    film.set_outlier_clamp(std::move(clamp));
}

}  // namespace snell
