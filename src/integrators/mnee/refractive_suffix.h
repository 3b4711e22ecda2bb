#pragma once
// What `mnee` remembers about a camera path beyond the path tracer, for the MIS weights of
// Alg. 2: the refractive suffix since the last vertex that connects to lights.
#include <array>
#include <cstddef>
#include <new>
#include <type_traits>

#include "core/medium_stack.h"
#include "geometry/interaction.h"
#include "manifold/mnee_settings.h"

namespace snell {

/// The refractive suffix of a path: the last vertex x_b that can connect to lights by MNEE
/// (non-delta, not a refractive interface) and the refractive vertices x_1..x_k sampled
/// after it, with the BSDF-sampling density of x_1..x_k in area measure (deltas of specular
/// vertices factored out in half-vector measure, paper Sec. 3.3 "Specular Case").
struct RefractiveSuffix {
    static constexpr int kMaxVertices = kMaxChainVertices;

    /// x_1..x_k, constructed as they are recorded: every camera sample makes a suffix, and
    /// value-initialising all kMaxVertices interactions showed in `mnee`'s profile where most
    /// regions make no connection (docs/experiments.md, "What a region at q = 0 costs").
    class Chain {
    public:
        static_assert(std::is_trivially_copyable_v<SurfaceInteraction> &&
                          std::is_trivially_destructible_v<SurfaceInteraction>,
                      "Chain neither copies nor destroys its interactions one by one");
        Chain() {}  // NOLINT: the storage is written before it is read
        void set(size_t i, const SurfaceInteraction& si) {
            new (m_bytes + i * sizeof(SurfaceInteraction)) SurfaceInteraction(si);
        }
        const SurfaceInteraction& operator[](size_t i) const { return data()[i]; }
        const SurfaceInteraction* data() const {
            return std::launder(reinterpret_cast<const SurfaceInteraction*>(m_bytes));
        }

    private:
        alignas(SurfaceInteraction) std::byte m_bytes[kMaxVertices * sizeof(SurfaceInteraction)];
    };

    bool has_xb = false;  ///< x_b exists and everything since is a refractive interface
    SurfaceInteraction xb;
    MediumStack xb_media;  ///< medium at x_b
    int k = 0;             ///< vertices recorded after x_b
    Chain chain;           ///< x_1..x_k (only [0, k) are constructed)
    std::array<bool, kMaxVertices> specular{};
    bool transmissions_only = true;  ///< all recorded vertices refract (MNEE can only produce those)
    double p_prefix = 1;             ///< area density of BSDF sampling x_1..x_k given x_b
    double q_last = 0;               ///< density of the last sampled direction (solid angle, deltas factored)

    /// A new x_b whose suffix no MIS weight reads (a region at q = 0): only what the
    /// statistics' technique names need (has_xb, k, transmissions_only).
    void restart() {
        has_xb = true;
        k = 0;
        transmissions_only = true;
    }
    /// A new x_b, reached in `media` and left by a direction of density q: the suffix starts
    /// empty.
    void start(const SurfaceInteraction& x, const MediumStack& media, double q) {
        restart();
        xb = x;
        xb_media = media;
        p_prefix = 1;
        q_last = q;
    }
};

}  // namespace snell
