#pragma once
#include <cstdint>

namespace snell {

/// PCG32 (O'Neill 2014): small state, good statistics, and cheap independent streams,
/// so every pixel sample can own a stream and renders do not depend on thread count.
class PCG32 {
public:
    PCG32() { seed(0x853c49e6748fea9bULL, 0xda3e39cb94b95bdbULL); }
    PCG32(uint64_t init_state, uint64_t stream) { seed(init_state, stream); }

    void seed(uint64_t init_state, uint64_t stream) {
        m_state = 0u;
        m_inc = (stream << 1u) | 1u;
        next_u32();
        m_state += init_state;
        next_u32();
    }
    uint32_t next_u32() {
        const uint64_t old = m_state;
        m_state = old * 0x5851f42d4c957f2dULL + m_inc;
        const uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
        const uint32_t rot = uint32_t(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
    }
    /// Uniform double in [0, 1) with 53 random bits.
    double next_double() {
        const uint64_t hi = next_u32(), lo = next_u32();
        return double(((hi << 32) | lo) >> 11) * 0x1.0p-53;
    }

private:
    uint64_t m_state, m_inc;
};

/// 64-bit mix (splitmix64 finaliser) to derive well-spread seeds from indices.
inline uint64_t mix_bits(uint64_t v) {
    v ^= v >> 31;
    v *= 0x7fb5d329728ea185ULL;
    v ^= v >> 27;
    v *= 0x81dadef4bc2dd44dULL;
    v ^= v >> 33;
    return v;
}

}  // namespace snell
