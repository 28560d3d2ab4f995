#pragma once
// perlin: book 2's gradient noise (Perlin, "Improving Noise", SIGGRAPH 2002, as the book builds
// it): a random unit vector at every lattice point, chosen through three permutations of 0..255,
// blended with Hermite weights, so the noise is smooth and tiles every 256 units.
//
//   perlin noise;                 draws its tables from random_double(), as the book does
//   noise.noise(p)                in about [-1, 1]; 0 at every lattice point
//   noise.turb(p, depth = 7)      |sum of depth octaves, each at twice the frequency and half
//                                 the weight of the last|
//
// The constructor draws exactly what the book's does, in the same order: 256 vectors of
// vec3::random(-1, 1) (three random_double() each: z, then y, then x, the order g++ evaluates the
// book's vec3(random_double(), ...) in; see vec3.h), then the shuffles of perm_x, perm_y and
// perm_z, each random_int(0, i) for i = 255 down to 1. Outside a render random_double() is the
// book's rand() / (RAND_MAX + 1.0), so a main that calls srand() as the book's would gets the
// book's noise; inside a render it is the sample's own generator (engine/rng.h), so a texture
// made there is still the same at any thread count.

#include "engine/rng.h"
#include "vec3.h"

#include <cmath>

namespace rt {

class perlin {
  public:
    perlin();

    double noise(const point3& p) const;
    double turb(const point3& p, int depth = 7) const;

    static constexpr int point_count = 256;

  private:
    vec3 randvec_[point_count];
    int perm_x_[point_count], perm_y_[point_count], perm_z_[point_count];

    static void generate_perm(int* p);
    static double interpolate(const vec3 c[2][2][2], double u, double v, double w);
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline perlin::perlin() {
    for (vec3& g : randvec_) g = unit_vector(vec3::random(-1, 1));
    generate_perm(perm_x_);
    generate_perm(perm_y_);
    generate_perm(perm_z_);
}

// The identity, shuffled from the top down (Fisher and Yates).
inline void perlin::generate_perm(int* p) {
    for (int i = 0; i < point_count; ++i) p[i] = i;
    for (int i = point_count - 1; i > 0; --i) {
        const int target = random_int(0, i);
        const int held = p[i];
        p[i] = p[target];
        p[target] = held;
    }
}

inline double perlin::noise(const point3& p) const {
    const double fx = std::floor(p.x()), fy = std::floor(p.y()), fz = std::floor(p.z());
    // The lattice cell's index modulo 256 (only its low 8 bits are used), taken in double: the
    // book's int(fx) is undefined beyond an int, which a point far from the origin (or a large
    // noise scale) reaches. The same indices as the book's wherever an int holds fx.
    auto wrap = [](double f) { return std::isfinite(f) ? int(f - 256.0 * std::floor(f / 256.0)) : 0; };
    const int i = wrap(fx), j = wrap(fy), k = wrap(fz);
    vec3 c[2][2][2];
    for (int di = 0; di < 2; ++di)
        for (int dj = 0; dj < 2; ++dj)
            for (int dk = 0; dk < 2; ++dk)
                c[di][dj][dk] = randvec_[perm_x_[(i + di) & 255] ^ perm_y_[(j + dj) & 255] ^ perm_z_[(k + dk) & 255]];
    return interpolate(c, p.x() - fx, p.y() - fy, p.z() - fz);
}

// Each corner's gradient dotted with the offset from that corner, weighted by the smoothstep
// (Hermite cubic 3t^2 - 2t^3) of the position in the cell, so the noise's slope is continuous.
inline double perlin::interpolate(const vec3 c[2][2][2], double u, double v, double w) {
    const double uu = u * u * (3 - 2 * u), vv = v * v * (3 - 2 * v), ww = w * w * (3 - 2 * w);
    double sum = 0;
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
            for (int k = 0; k < 2; ++k) {
                const vec3 offset(u - i, v - j, w - k);
                sum += (i * uu + (1 - i) * (1 - uu)) * (j * vv + (1 - j) * (1 - vv)) * (k * ww + (1 - k) * (1 - ww)) *
                       dot(c[i][j][k], offset);
            }
    return sum;
}

inline double perlin::turb(const point3& p, int depth) const {
    double sum = 0, weight = 1;
    point3 q = p;
    for (int octave = 0; octave < depth; ++octave) {
        sum += weight * noise(q);
        weight *= 0.5;
        q *= 2;
    }
    return std::fabs(sum);
}

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::perlin;
#endif
