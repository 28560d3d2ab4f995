#pragma once
// vec3: the book's three-component vector of doubles, used for points (point3), directions and
// colours (color) on the teaching surface. Scenes are described in double precision; the renderer
// converts them to float relative to the camera when it compiles the scene (see scene/scene_compiler.h), so a
// scene far from the origin keeps its precision.

#include "core/constants.h"
#include "core/rng.h"

#include <cmath>
#include <iostream>

namespace rt {

class vec3 {
  public:
    double e[3];

    constexpr vec3() : e{0, 0, 0} {}
    constexpr vec3(double e0, double e1, double e2) : e{e0, e1, e2} {}

    constexpr double x() const { return e[0]; }
    constexpr double y() const { return e[1]; }
    constexpr double z() const { return e[2]; }

    constexpr vec3 operator-() const { return vec3(-e[0], -e[1], -e[2]); }
    constexpr double operator[](int i) const { return e[i]; }
    constexpr double& operator[](int i) { return e[i]; }

    constexpr vec3& operator+=(const vec3& v) {
        e[0] += v.e[0];
        e[1] += v.e[1];
        e[2] += v.e[2];
        return *this;
    }
    constexpr vec3& operator*=(double t) {
        e[0] *= t;
        e[1] *= t;
        e[2] *= t;
        return *this;
    }
    constexpr vec3& operator/=(double t) { return *this *= 1 / t; }

    double length() const { return std::sqrt(length_squared()); }
    constexpr double length_squared() const { return e[0] * e[0] + e[1] * e[1] + e[2] * e[2]; }

    // True if the vector is close to zero in all dimensions.
    bool near_zero() const {
        constexpr double s = 1e-8;
        return std::fabs(e[0]) < s && std::fabs(e[1]) < s && std::fabs(e[2]) < s;
    }

    // A vector of independent uniform components. The book writes vec3(random_double(),
    // random_double(), random_double()), whose draw order C++ leaves to the compiler; g++
    // evaluates the arguments last to first, so the book's published scenes were drawn z, y, x.
    // We fix that order explicitly, so book-style mains build the book's scene with any compiler.
    static vec3 random() {
        double z = random_double(), y = random_double(), x = random_double();
        return vec3(x, y, z);
    }
    static vec3 random(double min, double max) {
        double z = random_double(min, max), y = random_double(min, max), x = random_double(min, max);
        return vec3(x, y, z);
    }
};

// point3 is just an alias for vec3, useful for geometric clarity in the code.
using point3 = vec3;

inline std::ostream& operator<<(std::ostream& out, const vec3& v) {
    return out << v.e[0] << ' ' << v.e[1] << ' ' << v.e[2];
}

constexpr vec3 operator+(const vec3& u, const vec3& v) { return vec3(u.e[0] + v.e[0], u.e[1] + v.e[1], u.e[2] + v.e[2]); }
constexpr vec3 operator-(const vec3& u, const vec3& v) { return vec3(u.e[0] - v.e[0], u.e[1] - v.e[1], u.e[2] - v.e[2]); }
constexpr vec3 operator*(const vec3& u, const vec3& v) { return vec3(u.e[0] * v.e[0], u.e[1] * v.e[1], u.e[2] * v.e[2]); }
constexpr vec3 operator*(double t, const vec3& v) { return vec3(t * v.e[0], t * v.e[1], t * v.e[2]); }
constexpr vec3 operator*(const vec3& v, double t) { return t * v; }
constexpr vec3 operator/(const vec3& v, double t) { return (1 / t) * v; }

constexpr double dot(const vec3& u, const vec3& v) { return u.e[0] * v.e[0] + u.e[1] * v.e[1] + u.e[2] * v.e[2]; }

constexpr vec3 cross(const vec3& u, const vec3& v) {
    return vec3(u.e[1] * v.e[2] - u.e[2] * v.e[1],
                u.e[2] * v.e[0] - u.e[0] * v.e[2],
                u.e[0] * v.e[1] - u.e[1] * v.e[0]);
}

inline vec3 unit_vector(const vec3& v) { return v / v.length(); }

// A uniformly distributed point inside the unit sphere (rejection from the enclosing cube), as
// earlier editions of the book use it.
inline vec3 random_in_unit_sphere() {
    while (true) {
        vec3 p = vec3::random(-1, 1);
        if (p.length_squared() < 1) return p;
    }
}

// A uniformly distributed point in the unit disk (z = 0), by rejection from the enclosing square
// as the book's is: the same draws in the same order (y, then x, the order g++ evaluates the
// book's vec3(random_double(-1, 1), random_double(-1, 1), 0) in), so a main that calls it outside
// a render gets the book's numbers.
inline vec3 random_in_unit_disk() {
    while (true) {
        double y = random_double(-1, 1), x = random_double(-1, 1);
        if (x * x + y * y < 1) return vec3(x, y, 0);
    }
}

// A uniformly distributed direction on the unit sphere: a point of the cube accepted inside the
// ball and projected onto the sphere, as the book's is (the same draws; a point too near the
// centre to normalise, below 1e-160 in squared length, is drawn again).
inline vec3 random_unit_vector() {
    while (true) {
        vec3 p = vec3::random(-1, 1);
        double length_squared = p.length_squared();
        if (1e-160 < length_squared && length_squared <= 1) return p / std::sqrt(length_squared);
    }
}

// A uniformly distributed direction on the hemisphere around `normal`.
inline vec3 random_on_hemisphere(const vec3& normal) {
    vec3 on_unit_sphere = random_unit_vector();
    return dot(on_unit_sphere, normal) > 0.0 ? on_unit_sphere : -on_unit_sphere;
}

// The older books' (v3) point of the half of the unit ball on `normal`'s side: uniform in it.
inline vec3 random_in_hemisphere(const vec3& normal) {
    vec3 in_unit_sphere = random_in_unit_sphere();
    return dot(in_unit_sphere, normal) > 0.0 ? in_unit_sphere : -in_unit_sphere;
}

// A direction on the hemisphere around +z with density cos(theta) / pi (book 3): r2 = sin^2 theta
// is uniform, because the projected disk area under a cosine lobe grows linearly with it, and
// phi = 2 pi r1 goes round the axis.
inline vec3 random_cosine_direction() {
    double r1 = random_double();
    double r2 = random_double();
    double phi = 2 * pi * r1;
    double sin_theta = std::sqrt(r2);
    return vec3(std::cos(phi) * sin_theta, std::sin(phi) * sin_theta, std::sqrt(1 - r2));
}

// Mirror reflection of v about the unit normal n.
constexpr vec3 reflect(const vec3& v, const vec3& n) { return v - 2 * dot(v, n) * n; }

// Refraction of the unit vector uv through a surface with unit normal n (facing uv's side), for
// the ratio etai_over_etat of refractive indices (Snell's law, split into perpendicular and
// parallel parts as in the book).
inline vec3 refract(const vec3& uv, const vec3& n, double etai_over_etat) {
    double cos_theta = std::fmin(dot(-uv, n), 1.0);
    vec3 r_out_perp = etai_over_etat * (uv + cos_theta * n);
    vec3 r_out_parallel = -std::sqrt(std::fabs(1.0 - r_out_perp.length_squared())) * n;
    return r_out_perp + r_out_parallel;
}

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
// The book's headers declare these names globally; so do ours, for book-style mains. Define
// RTWEEKEND_NO_GLOBAL_NAMES to keep everything inside namespace rt.
using rt::cross;
using rt::dot;
using rt::point3;
using rt::random_in_unit_disk;
using rt::random_cosine_direction;
using rt::random_in_unit_sphere;
using rt::random_on_hemisphere;
using rt::random_in_hemisphere;
using rt::random_unit_vector;
using rt::reflect;
using rt::refract;
using rt::unit_vector;
using rt::vec3;
#endif
