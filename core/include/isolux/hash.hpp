// Deterministic hashing, random numbers and noise: the same seed gives the same
// values with every compiler and standard library (no std::*_distribution).
#pragma once
#include <cstdint>
#include <string_view>

namespace isolux {

// FNV-1a 64-bit over the seed's bytes, then the SplitMix64 finaliser so that
// near-identical seeds ("a", "b") give unrelated 64-bit states.
std::uint64_t hash_seed(std::string_view seed);

// The SplitMix64 finaliser (Steele, Lea and Flood 2014): a strong 64-bit mixer.
std::uint64_t mix64(std::uint64_t x);

// Hash of a lattice point under a seed, for noise and per-tile choices.
std::uint64_t hash_point(std::uint64_t seed, std::int64_t x, std::int64_t y, std::uint64_t salt = 0);

// PCG32 (O'Neill 2014, pcg32_random_r): the project's PRNG.
struct Pcg32 {
    std::uint64_t state = 0, inc = 1;
    explicit Pcg32(std::uint64_t seed, std::uint64_t stream = 54);
    std::uint32_t next();
    // Uniform integer in [0, n) by Lemire's multiply-shift with rejection: the
    // same on every platform.
    std::uint32_t below(std::uint32_t n);
    // Uniform double in [0, 1) from 32 random bits.
    double unit();
};

// Value noise in [0, 1] at (x, y) with lattice spacing 1: hashed lattice
// values, smoothstep interpolation. Only +, -, *, / so it is bit-exact across
// machines (the build turns off FP contraction).
double value_noise(std::uint64_t seed, double x, double y);

// Fractal sum of value noise: `octaves` layers, each twice the frequency and
// half the amplitude of the one before, normalised to [0, 1].
double fractal_noise(std::uint64_t seed, double x, double y, int octaves);

}  // namespace isolux
