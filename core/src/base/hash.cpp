#include "isolux/hash.hpp"

namespace isolux {

std::uint64_t mix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

std::uint64_t hash_seed(std::string_view seed) {
    std::uint64_t h = 0xCBF29CE484222325ull;  // FNV-1a 64 offset basis
    for (unsigned char c : seed) {
        h ^= c;
        h *= 0x100000001B3ull;  // FNV-1a 64 prime
    }
    return mix64(h);
}

std::uint64_t hash_point(std::uint64_t seed, std::int64_t x, std::int64_t y, std::uint64_t salt) {
    std::uint64_t h = mix64(seed ^ mix64(salt));
    h = mix64(h ^ std::uint64_t(x));
    return mix64(h ^ (std::uint64_t(y) * 0x9E3779B97F4A7C15ull));
}

Pcg32::Pcg32(std::uint64_t seed, std::uint64_t stream) {
    inc = (stream << 1u) | 1u;
    state = 0;
    next();
    state += seed;
    next();
}

std::uint32_t Pcg32::next() {
    std::uint64_t old = state;
    state = old * 6364136223846793005ull + inc;
    auto xorshifted = std::uint32_t(((old >> 18u) ^ old) >> 27u);
    auto rot = std::uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
}

std::uint32_t Pcg32::below(std::uint32_t n) {
    if (n <= 1) return 0;
    std::uint64_t m = std::uint64_t(next()) * n;
    auto low = std::uint32_t(m);
    if (low < n) {
        std::uint32_t t = (0u - n) % n;
        while (low < t) {
            m = std::uint64_t(next()) * n;
            low = std::uint32_t(m);
        }
    }
    return std::uint32_t(m >> 32);
}

double Pcg32::unit() { return next() * (1.0 / 4294967296.0); }

namespace {
double lattice(std::uint64_t seed, std::int64_t x, std::int64_t y) {
    return double(hash_point(seed, x, y) >> 11) * (1.0 / 9007199254740992.0);
}
double smooth(double t) { return t * t * (3.0 - 2.0 * t); }
std::int64_t floor_i(double v) {
    auto i = std::int64_t(v);
    return (double(i) > v) ? i - 1 : i;
}
}  // namespace

double value_noise(std::uint64_t seed, double x, double y) {
    std::int64_t ix = floor_i(x), iy = floor_i(y);
    double fx = smooth(x - double(ix)), fy = smooth(y - double(iy));
    double a = lattice(seed, ix, iy), b = lattice(seed, ix + 1, iy);
    double c = lattice(seed, ix, iy + 1), d = lattice(seed, ix + 1, iy + 1);
    double top = a + (b - a) * fx, bottom = c + (d - c) * fx;
    return top + (bottom - top) * fy;
}

double fractal_noise(std::uint64_t seed, double x, double y, int octaves) {
    double sum = 0, amp = 1, norm = 0, freq = 1;
    for (int o = 0; o < octaves; ++o) {
        sum += amp * value_noise(mix64(seed + std::uint64_t(o)), x * freq, y * freq);
        norm += amp;
        amp *= 0.5;
        freq *= 2.0;
    }
    return sum / norm;
}

}  // namespace isolux
