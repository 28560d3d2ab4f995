#pragma once
// Random numbers.
//
//   pcg32              a small, fast generator (O'Neill, "PCG: A Family of Simple Fast
//                      Space-Efficient Statistically Good Algorithms", 2014), passed explicitly.
//   sample_rng(...)    the generator for one camera sample, seeded from (seed, pixel, sample) so
//                      an image never depends on thread count or tile order.
//   random_double()    the book's free function. Outside a render it is the book's own
//                      rand() / (RAND_MAX + 1.0), so a book-style main builds exactly the scene the
//                      book builds with the same C library. Inside a render it draws from the
//                      current sample's generator, so user-written materials and shapes that call
//                      it stay deterministic at any thread count.

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <utility>

namespace rt {

struct uniform2;
template <class U>
constexpr auto has_next_2d(int) -> decltype(std::declval<U&>().next_2d(), bool()) { return true; }
template <class U>
constexpr bool has_next_2d(long) { return false; }

// SplitMix64's finaliser (Steele, Lea and Flood, OOPSLA 2014): a bijective 64-bit mix.
inline constexpr uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

class pcg32 {
  public:
    constexpr pcg32() = default;
    explicit constexpr pcg32(uint64_t seed, uint64_t stream = 0xda3e39cb94b95bdbULL) { reseed(seed, stream); }

    constexpr void reseed(uint64_t seed, uint64_t stream) {
        state_ = 0;
        inc_ = (stream << 1u) | 1u;
        next_u32();
        state_ += seed;
        next_u32();
    }

    constexpr uint32_t next_u32() {
        uint64_t old = state_;
        state_ = old * 6364136223846793005ULL + inc_;
        auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
        auto rot = static_cast<uint32_t>(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
    }

    // A generator of its own, seeded from a hash of this one's state on another stream, this one
    // not advanced: for numbers that must not shift this stream's (the light path a camera
    // sample traces, path_tracer.h, beside the numbers of the sample's own path).
    constexpr pcg32 split() const { return pcg32(mix64(state_ ^ 0x2545f4914f6cdd1dULL), mix64(inc_)); }

    // Uniform in [0, 1): 24 random bits, so the result is exactly representable and never 1.
    constexpr float next_float() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }
    // Uniform in [0, 1) with 53 random bits.
    constexpr double next_double() {
        uint64_t hi = next_u32() >> 5, lo = next_u32() >> 6;
        return static_cast<double>((hi << 26) | lo) * 0x1p-53;
    }

  private:
    uint64_t state_ = 0x853c49e6748fea9bULL;
    uint64_t inc_ = 0xda3e39cb94b95bdbULL;
};

// Two uniforms drawn together: a 2-D decision (a direction, a point on a light or a lens).
struct uniform2 {
    float u1, u2;
};

// A pair from any source of uniforms `u`: its next_2d() when it has one (a sampler that
// stratifies pairs, sampler.h), else two next_float() in order.
template <class Uniform>
uniform2 draw_2d(Uniform& u) {
    if constexpr (has_next_2d<Uniform>(0)) {
        return u.next_2d();
    } else {
        const float u1 = u.next_float();
        const float u2 = u.next_float();
        return {u1, u2};
    }
}

// The generator for sample `sample` of pixel `pixel` in a render seeded with `seed`.
inline constexpr pcg32 sample_rng(uint64_t seed, uint64_t pixel, uint64_t sample) {
    uint64_t h = mix64(seed + 0x9e3779b97f4a7c15ULL);
    h = mix64(h ^ (pixel + 0x632be59bd9b4e019ULL));
    h = mix64(h ^ (sample * 0xd6e8feb86659fd93ULL));
    return pcg32(h, pixel ^ (sample << 32));
}

namespace detail {
// The generator of the camera sample this thread is computing, or null outside a render. The
// renderer installs it only around calls into user-written code (see path_tracer.h).
inline pcg32*& thread_sample_rng() {
    thread_local pcg32* current = nullptr;
    return current;
}

// Installs `g` as this thread's sample generator for the lifetime of the guard.
class scoped_sample_rng {
  public:
    explicit scoped_sample_rng(pcg32& g) : previous_(thread_sample_rng()) { thread_sample_rng() = &g; }
    ~scoped_sample_rng() { thread_sample_rng() = previous_; }
    scoped_sample_rng(const scoped_sample_rng&) = delete;
    scoped_sample_rng& operator=(const scoped_sample_rng&) = delete;

  private:
    pcg32* previous_;
};
} // namespace detail

// Returns a random real in [0,1).
inline double random_double() {
    if (pcg32* g = detail::thread_sample_rng()) return g->next_double();
    return std::rand() / (RAND_MAX + 1.0);
}

// Returns a random real in [min,max).
inline double random_double(double min, double max) { return min + (max - min) * random_double(); }

// Returns a random integer in [min,max].
inline int random_int(int min, int max) { return static_cast<int>(std::floor(random_double(min, max + 1.0))); }

} // namespace rt
