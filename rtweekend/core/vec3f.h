#pragma once
// vec3f: the renderer's single-precision vector. The teaching surface describes scenes with the
// book's double vec3; the compiled scene (scene/compiled_scene.h) and the render loop work in float.
//
// core/ stands below the books' headers, so this one does not include vec3.h: the conversions to
// and from the book's vec3 are templates, which need vec3 only where they are used (and every
// such place has included vec3.h).

#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>
#if defined(__SSE__)
#include <immintrin.h>
#endif

namespace rt {

class vec3; // the books' vector in double (vec3.h)

// std::fmax and std::fmin as glibc computes them (a NaN loses to a number; of two equal values,
// zeros of either sign included, the first), as selects the compiler puts inline: GCC compiles
// std::fmax to a call of the C library's, and the path tracer asked for one in every bounce.
template <class T>
constexpr T fmax_inline(T a, T b) { return b > a || a != a ? b : a; }
template <class T>
constexpr T fmin_inline(T a, T b) { return b < a || a != a ? b : a; }

// A float's bits as an unsigned integer and back, for the branch-free selects and sign flips of
// the hot loop (ray_offset.h, sampling.h): integer masks where the compiler would branch.
inline uint32_t float_bits(float f) { uint32_t u; std::memcpy(&u, &f, sizeof u); return u; }
inline float bits_float(uint32_t u) { float f; std::memcpy(&f, &u, sizeof f); return f; }

// A float's square root, one instruction. std::sqrt may set errno (for a negative argument), so
// unless a program is built with -fno-math-errno GCC puts a test and a call of the C library's
// sqrtf beside each one; in a function of the hot loop that call's register saves cost more than
// the root. The same IEEE result (NaN for a negative argument). Doubles go to std::sqrt.
inline float sqrt_f(float x) {
#if defined(__SSE__)
    return _mm_cvtss_f32(_mm_sqrt_ss(_mm_set_ss(x)));
#else
    return std::sqrt(x);
#endif
}
float sqrt_f(double) = delete;

struct vec3f {
    float x = 0, y = 0, z = 0;

    constexpr vec3f() = default;
    constexpr vec3f(float x, float y, float z) : x(x), y(y), z(z) {}
    // The book's vec3 (or color, or point3), each coordinate rounded to float.
    template <class V, std::enable_if_t<std::is_same_v<V, vec3>, int> = 0>
    constexpr explicit vec3f(const V& v)
        : x(static_cast<float>(v.x())), y(static_cast<float>(v.y())), z(static_cast<float>(v.z())) {}

    constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr vec3f operator-() const { return {-x, -y, -z}; }
    constexpr vec3f& operator+=(const vec3f& v) { x += v.x; y += v.y; z += v.z; return *this; }
    constexpr vec3f& operator*=(const vec3f& v) { x *= v.x; y *= v.y; z *= v.z; return *this; }
    constexpr vec3f& operator*=(float t) { x *= t; y *= t; z *= t; return *this; }

    // As the book's vec3, exactly.
    template <class V = vec3>
    V to_double() const { return V(x, y, z); }
};

constexpr vec3f operator+(const vec3f& a, const vec3f& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr vec3f operator-(const vec3f& a, const vec3f& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr vec3f operator*(const vec3f& a, const vec3f& b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
constexpr vec3f operator*(float t, const vec3f& v) { return {t * v.x, t * v.y, t * v.z}; }
constexpr vec3f operator*(const vec3f& v, float t) { return t * v; }
constexpr vec3f operator/(const vec3f& v, float t) { return (1.0f / t) * v; }

constexpr float dot(const vec3f& a, const vec3f& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr vec3f cross(const vec3f& a, const vec3f& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
constexpr float length_squared(const vec3f& v) { return dot(v, v); }
inline float length(const vec3f& v) { return sqrt_f(dot(v, v)); }
inline vec3f normalize(const vec3f& v) { return v * (1.0f / length(v)); }
inline float max_abs_component(const vec3f& v) { return fmax_inline(std::fabs(v.x), fmax_inline(std::fabs(v.y), std::fabs(v.z))); }
inline bool is_finite(const vec3f& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The renderer's ray: origin, unit direction, the open parameter range (tmin, tmax), and the
// moment in the shutter interval [0, 1) it samples (book 2's motion blur): only moving shapes
// read it; every ray spawned along a path keeps its camera ray's time.
struct ray3f {
    vec3f origin;
    vec3f dir;
    float tmin = 0;
    float tmax = std::numeric_limits<float>::infinity();
    float time = 0;

    vec3f at(float t) const { return origin + t * dir; }
};

namespace detail {
// Whether no channel of c is positive (black, or NaN).
inline bool is_black(const vec3f& c) { return !(c.x > 0 || c.y > 0 || c.z > 0); }
} // namespace detail

} // namespace rt
