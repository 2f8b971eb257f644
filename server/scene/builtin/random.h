#pragma once
// Deterministic randomness for the built-in scenes: PCG32 (O'Neill, pcg-random.org, XSH-RR
// variant) with a fixed seed per scene, and an integer hash for lattice noise. No global state,
// so a scene builds the same way every time, on every thread.
#include <cstdint>

namespace strata::scene::builtin {

class Pcg32 {
 public:
  explicit Pcg32(uint64_t seed, uint64_t stream = 54u) : increment_((stream << 1u) | 1u) {
    next();
    state_ += seed;
    next();
  }
  uint32_t next() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ull + increment_;
    const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  // Uniform in [0, 1) with 24 bits, exact in float.
  float uniform() { return static_cast<float>(next() >> 8) * (1.0f / 16777216.0f); }
  float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }

 private:
  uint64_t state_ = 0;
  uint64_t increment_;
};

// A well-mixed 32-bit hash of two lattice coordinates and a seed (lowbias32-style finaliser).
inline uint32_t hash2(int32_t x, int32_t y, uint32_t seed) {
  uint32_t h = static_cast<uint32_t>(x) * 0x8da6b343u ^ static_cast<uint32_t>(y) * 0xd8163841u ^
               seed * 0xcb1ab31fu;
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return h;
}

}  // namespace strata::scene::builtin
