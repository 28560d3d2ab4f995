#pragma once
// microfacet: the GGX (Trowbridge-Reitz) distribution of microfacet normals, which the rough
// material kinds share (core/materials/rough_conductor_bsdf.h, rough_dielectric_bsdf.h,
// metal_rough_bsdf.h).
//
//   microfacet_frame f(n);                 a tangent frame about the shading normal
//   ggx g{alpha_u, alpha_v};               roughness along the frame's tangent and bitangent
//   g.d(m), g.g1(w), g.g2(wo, wi)          the distribution and Smith's masking(-shadowing)
//   g.sample_visible(wo, u1, u2)           a normal drawn from the normals wo sees
//   g.visible_pdf(wo, m)                   its density
//   ggx_albedo().albedo(mu, alpha)         what a white GGX mirror reflects at cosine mu, and
//   ggx_albedo().average(alpha)            its cosine-weighted mean: the energy compensation's tables
//   ggx_albedo().albedo(mu, alpha, f0)     the same for Schlick's Fresnel from f0 (a clear coat)
//   sample_in_frame(wo, n, u, s, draw, eval, pdf)   what the rough kinds' sample() share
//
// Directions in the frame's coordinates: z along the normal. Roughness r in [0, 1] maps to
// alpha = r^2 (the perceptual mapping of Burley's "Physically Based Shading at Disney", 2012, and
// of glTF 2.0's metallic-roughness material).
//
// The formulas:
//   D(m) = 1 / (pi au av (mx^2/au^2 + my^2/av^2 + mz^2)^2)        (Walter, Marschner, Li and
//        Torrance, "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007, eq. 33,
//        in its anisotropic form: Heitz, "Understanding the Masking-Shadowing Function in
//        Microfacet-Based BRDFs", JCGT 3(2), 2014, eq. 85)
//   Lambda(w) = (sqrt(1 + (au^2 wx^2 + av^2 wy^2) / wz^2) - 1) / 2    (Heitz 2014, eq. 86)
//   G1(w) = 1 / (1 + Lambda(w)), G2(wo, wi) = 1 / (1 + Lambda(wo) + Lambda(wi))
//        (the height-correlated masking-shadowing function, Heitz 2014, eq. 99)
//   D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo.z    (the visible normals, Heitz 2014, eq. 38)
// and the visible normals are drawn by Heitz's "Sampling the GGX Distribution of Visible Normals",
// JCGT 7(4), 2018: stretch wo to the unit-roughness configuration, draw a point of the projected
// hemisphere, unstretch.
//
// Anisotropy needs a tangent, which a shading point does not carry: microfacet_frame takes it
// around the world's y axis (t = y x n, normalised): a sphere's rough_u runs along its circles of
// latitude, as on a turned or spun metal part. Where n is along y the frame is any.

#include "bsdf.h"
#include "constants.h"
#include "rng.h"
#include "sampling.h"
#include "vec3f.h"

#include <cmath>

namespace rt {

// Below this alpha (on both axes) the rough kinds are smooth: delta lobes, as pbrt-v4 does for
// alpha below 1e-3 (its TrowbridgeReitzDistribution::EffectivelySmooth): the lobe would be
// narrower than float directions resolve well.
inline constexpr float smooth_alpha = 1e-3f;

// alpha for a roughness in [0, 1] (any finite value >= 0 is accepted: r^2).
inline float alpha_of_roughness(float roughness) { return roughness * roughness; }

struct microfacet_frame {
    vec3f t, b, n;
    explicit microfacet_frame(const vec3f& normal) : n(normal) {
        const vec3f around_y{n.z, 0.0f, -n.x}; // y x n
        const float len2 = around_y.x * around_y.x + around_y.z * around_y.z;
        if (len2 > 1e-8f) {
            t = around_y * (1.0f / std::sqrt(len2));
            b = cross(n, t);
        } else {
            frame_across(n, t, b);
        }
    }
    vec3f to_local(const vec3f& v) const { return {dot(v, t), dot(v, b), dot(v, n)}; }
    vec3f to_world(const vec3f& v) const { return v.x * t + v.y * b + v.z * n; }
};

struct ggx {
    float alpha_u = 0.1f, alpha_v = 0.1f;

    bool smooth() const { return alpha_u < smooth_alpha && alpha_v < smooth_alpha; }
    bool isotropic() const { return alpha_u == alpha_v; }


    float d(const vec3f& m) const {
        if (!(m.z > 0)) return 0;
        const float x = m.x / alpha_u, y = m.y / alpha_v, s = x * x + y * y + m.z * m.z;
        return 1.0f / (pi_f * alpha_u * alpha_v * s * s);
    }
    float lambda(const vec3f& w) const {
        const float z2 = w.z * w.z;
        const float a2 = alpha_u * alpha_u * w.x * w.x + alpha_v * alpha_v * w.y * w.y;
        if (!(z2 > 0)) return a2 > 0 ? 1e30f : 0.0f;
        return 0.5f * (std::sqrt(1.0f + a2 / z2) - 1.0f);
    }
    float g1(const vec3f& w) const { return 1.0f / (1.0f + lambda(w)); }
    float g2(const vec3f& wo, const vec3f& wi) const { return 1.0f / (1.0f + lambda(wo) + lambda(wi)); }

    // The density of the normal m among those wo sees (wo.z > 0).
    float visible_pdf(const vec3f& wo, const vec3f& m) const {
        const float c = dot(wo, m);
        if (!(c > 0 && wo.z > 0)) return 0;
        return g1(wo) * c * d(m) / wo.z;
    }

    // A normal drawn with visible_pdf(wo, .) from (u1, u2) in [0, 1)^2 (Heitz 2018, listing 1).
    vec3f sample_visible(const vec3f& wo, float u1, float u2) const {
        const vec3f vh = normalize(vec3f{alpha_u * wo.x, alpha_v * wo.y, wo.z}); // stretched
        const float len2 = vh.x * vh.x + vh.y * vh.y;
        const vec3f t1 = len2 > 0 ? vec3f{-vh.y, vh.x, 0.0f} * (1.0f / std::sqrt(len2)) : vec3f{1, 0, 0};
        const vec3f t2 = cross(vh, t1);
        // A point of the unit disk, its lower half squeezed onto the part of the projected
        // hemisphere that vh sees.
        const float r = std::sqrt(u1);
        const vec3f c = unit_circle(u2);
        const float p1 = r * c.x, s = 0.5f * (1.0f + vh.z);
        const float p2 = (1.0f - s) * std::sqrt(fmax_inline(0.0f, 1.0f - p1 * p1)) + s * r * c.y;
        const vec3f nh = p1 * t1 + p2 * t2 + std::sqrt(fmax_inline(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
        return normalize(vec3f{alpha_u * nh.x, alpha_v * nh.y, fmax_inline(1e-7f, nh.z)}); // unstretched
    }
};

// What the rough kinds' sample() share: wo in the frame of the shading normal n (nothing drawn
// when it is below), the kind's draw(o, u0, u1, u2, i) of a local direction i (false: none), and
// its weight, worked out at the unit world direction as eval() and pdf() will see it:
// local_pdf(o, i) and local_eval(o, i) / local_pdf(o, i).
template <class Uniform, class Draw, class LocalEval, class LocalPdf>
bool sample_in_frame(const vec3f& wo, const vec3f& n, Uniform& u, material_sample& s, Draw&& draw,
                     LocalEval&& local_eval, LocalPdf&& local_pdf) {
    const microfacet_frame f(n);
    const vec3f o = f.to_local(wo);
    if (!(o.z > 0)) return false;
    const float u0 = u.next_float();
    const auto [u1, u2] = draw_2d(u);
    vec3f i;
    if (!draw(o, u0, u1, u2, i)) return false;
    s.wi = normalize(f.to_world(i));
    i = f.to_local(s.wi);
    s.pdf = local_pdf(o, i);
    if (!(s.pdf > 0)) return false;
    s.value = local_eval(o, i) * (1.0f / s.pdf);
    s.sampled = non_delta_lobe;
    return true;
}

// local(o, i) for wo and wi in the frame of the shading normal n: the rough kinds' eval and pdf.
template <class Local>
auto in_frame(const vec3f& n, const vec3f& wo, const vec3f& wi, Local&& local) {
    const microfacet_frame f(n);
    return local(f.to_local(wo), f.to_local(wi));
}

// The draw of a mirror and a diffuse-like lobe (rough_conductor_bsdf's multiple scattering,
// metal_rough_bsdf's base): with probability p_mirror wo reflected about a visible normal, else
// a cosine-weighted direction; in the local frame. False when the reflection falls below.
inline bool draw_mirror_or_cosine(const ggx& g, const vec3f& o, float p_mirror, float u0, float u1, float u2, vec3f& i) {
    if (u0 < p_mirror) {
        const vec3f m = g.sample_visible(o, u1, u2);
        i = 2.0f * dot(o, m) * m - o;
    } else {
        i = sample_cosine_direction(vec3f{0, 0, 1}, u1, u2);
    }
    return i.z > 0;
}

// The density of draw_mirror_or_cosine's direction i (local, above the surface).
inline float mirror_or_cosine_pdf(const ggx& g, const vec3f& o, const vec3f& i, float p_mirror) {
    const vec3f h = normalize(o + i);
    return p_mirror * g.visible_pdf(o, h) / (4.0f * dot(o, h)) + (1.0f - p_mirror) * i.z * (1.0f / pi_f);
}

namespace detail {
// 2 int E(mu) mu dmu of the function linear between values e[i] at cosines i / (n - 1): the
// segment [a, b] contributes (b - a) (E_a (2a + b) + E_b (a + 2b)) / 6. The compensation's mean is
// taken of the interpolant the lookups give, so that its lobe's albedo is exactly 1 - E(mu_o) as
// looked up.
inline double cosine_weighted_mean(const float* e, int n) {
    double sum = 0;
    for (int i = 0; i + 1 < n; ++i) {
        const double a = double(i) / (n - 1), b = double(i + 1) / (n - 1);
        sum += 2.0 * (b - a) * (e[i] * (2 * a + b) + e[i + 1] * (a + 2 * b)) / 6.0;
    }
    return sum;
}
// The node cosines of the albedo tables: 0 to 1 in even steps, the first taken at 0.002 (at 0
// the direction lies in the surface).
inline float albedo_node_mu(int i, int n) { return i == 0 ? 0.002f : float(i) / float(n - 1); }
// The node below x in [0, n - 1] and the weight of the one above.
inline int albedo_cell(float x, int n, float& w) {
    x = fmin_inline(fmax_inline(x, 0.0f), float(n - 1));
    int i = int(x);
    if (i >= n - 1) i = n - 2;
    w = x - float(i);
    return i;
}
} // namespace detail

// The directional albedo E(mu) of a white GGX mirror (Fresnel 1, single scattering), what it
// reflects of light arriving at cosine mu, and its cosine-weighted mean E_avg = 2 int E(mu) mu dmu,
// tabulated over mu and roughness for the energy compensation of Kulla and Conty ("Revisiting
// Physically Based Shading at Imageworks", SIGGRAPH 2017 course): the light single scattering
// loses, 1 - E, comes back through a lobe f_ms = (1 - E(mu_o)) (1 - E(mu_i)) / (pi (1 - E_avg)),
// whose albedo is exactly 1 - E(mu_o), so a white rough mirror reflects everything.
//
// With Schlick's Fresnel F = f0 + (1 - f0)(1 - wo.m)^5 in place of 1 the albedo is linear in f0:
// f0 E + (1 - f0) E5, with E5 the albedo weighted by (1 - wo.m)^5, tabulated beside E (the split
// of Karis, "Real Shading in Unreal Engine 4", SIGGRAPH 2013 course).
//
// Computed once, on first use, by quadrature over the visible normals (E(mu) is the mean of
// G2 / G1 over them, Heitz 2018, section 2.3, with 0 where the reflected direction falls below the
// surface; ggx_directional_albedo): 2048 directions at each of 32 x 32 nodes, some 60 ms; a scene
// without rough materials never builds it. Anisotropic roughness is looked up at sqrt(alpha_u alpha_v).
class ggx_albedo_table {
  public:
    static constexpr int mu_nodes = 32, roughness_nodes = 32;

    ggx_albedo_table();
    // E(mu) at alpha (bilinear between nodes); with f0, under Schlick's Fresnel.
    float albedo(float mu, float alpha) const { return lookup(e_, mu, alpha); }
    float albedo(float mu, float alpha, float f0) const {
        return f0 * albedo(mu, alpha) + (1.0f - f0) * lookup(e5_, mu, alpha);
    }
    // E_avg at alpha; with f0, under Schlick's Fresnel.
    float average(float alpha) const { return lookup_average(average_, alpha); }
    float average(float alpha, float f0) const {
        return f0 * average(alpha) + (1.0f - f0) * lookup_average(average5_, alpha);
    }

  private:
    using grid = float[roughness_nodes][mu_nodes];
    grid e_, e5_;
    float average_[roughness_nodes], average5_[roughness_nodes];
    static float lookup(const grid& g, float mu, float alpha);
    static float lookup_average(const float (&a)[roughness_nodes], float alpha);
    static float mu_at(int i) { return detail::albedo_node_mu(i, mu_nodes); }
    static float roughness_at(int j) { return float(j) / float(roughness_nodes - 1); }
    // The roughness node below alpha and the weight of the one above it.
    static void roughness_cell(float alpha, int& j, float& w);
};

// The table, built once (thread-safe), immutable after.
const ggx_albedo_table& ggx_albedo();

// The same for one anisotropic distribution, whose albedo depends on the azimuth too: E over 32
// cosines by 9 azimuths in [0, pi/2] (D and G2 are even in x and y), and its cosine-weighted mean
// over the hemisphere. Built per material (some 20 ms), held by the material that owns it.
class ggx_anisotropic_albedo {
  public:
    static constexpr int mu_nodes = 32, phi_nodes = 9;
    explicit ggx_anisotropic_albedo(const ggx& g);
    float albedo(const vec3f& w) const; // w in the distribution's frame
    float average() const { return average_; }

  private:
    float e_[phi_nodes][mu_nodes];
    float average_ = 1;
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

// E(mu) of a white GGX mirror towards wo (in its frame), and with `e5` the same weighted by
// (1 - wo.m)^5, by the quadrature below: u1 = 1 - (1 - t)^4 at 128 midpoints in t (weight
// 4 (1 - t)^3) and 16 midpoints in u2. What single scattering loses comes from grazing
// microfacets, the draws of u1 near 1 (GGX's long tail): even 256 x 256 plain midpoints, whose
// last u1 is 1 - 1/512, reported 0.99994 for roughness 0.19 where the loss is 0.0015 (0.99851 by
// 4 M random draws); the warp reaches u1 = 1 - 4e-10 and agreed with 16 M random draws within
// 1.5e-4 at every node tried (tests/test_microfacet.cpp checks it against random draws of its own).
inline double ggx_directional_albedo(const ggx& g, const vec3f& wo, double* e5 = nullptr) {
    constexpr int t_nodes = 128, azimuths = 16;
    double sum = 0, sum5 = 0;
    for (int a = 0; a < t_nodes; ++a) {
        const double t = (a + 0.5) / t_nodes, r = 1.0 - t, r3 = r * r * r;
        const float u1 = float(1.0 - r3 * r);
        const double jacobian = 4.0 * r3;
        for (int b = 0; b < azimuths; ++b) {
            const vec3f m = g.sample_visible(wo, u1, (float(b) + 0.5f) / azimuths);
            const float c = dot(wo, m);
            const vec3f wi = 2.0f * c * m - wo;
            if (!(wi.z > 0)) continue;
            const double w = jacobian * g.g2(wo, wi) / g.g1(wo), x = 1.0 - c;
            sum += w;
            sum5 += w * x * x * x * x * x;
        }
    }
    if (e5) *e5 = sum5 / (t_nodes * azimuths);
    return sum / (t_nodes * azimuths);
}


inline ggx_albedo_table::ggx_albedo_table() {
    for (int j = 0; j < roughness_nodes; ++j) {
        const float alpha = fmax_inline(alpha_of_roughness(roughness_at(j)), smooth_alpha);
        const ggx g{alpha, alpha};
        for (int i = 0; i < mu_nodes; ++i) {
            const float mu = mu_at(i);
            double e5 = 0;
            e_[j][i] = float(ggx_directional_albedo(g, vec3f{std::sqrt(1.0f - mu * mu), 0.0f, mu}, &e5));
            e5_[j][i] = float(e5);
        }
        average_[j] = float(detail::cosine_weighted_mean(e_[j], mu_nodes));
        average5_[j] = float(detail::cosine_weighted_mean(e5_[j], mu_nodes));
    }
}

inline void ggx_albedo_table::roughness_cell(float alpha, int& j, float& w) {
    j = detail::albedo_cell(std::sqrt(fmax_inline(alpha, 0.0f)) * (roughness_nodes - 1), roughness_nodes, w);
}

inline float ggx_albedo_table::lookup(const grid& e, float mu, float alpha) {
    int j;
    float wr, wm;
    roughness_cell(alpha, j, wr);
    const int i = detail::albedo_cell(mu * (mu_nodes - 1), mu_nodes, wm);
    const float lo = e[j][i] + wm * (e[j][i + 1] - e[j][i]);
    const float hi = e[j + 1][i] + wm * (e[j + 1][i + 1] - e[j + 1][i]);
    return lo + wr * (hi - lo);
}

inline float ggx_albedo_table::lookup_average(const float (&a)[roughness_nodes], float alpha) {
    int j;
    float w;
    roughness_cell(alpha, j, w);
    return a[j] + w * (a[j + 1] - a[j]);
}

inline ggx_anisotropic_albedo::ggx_anisotropic_albedo(const ggx& g) {
    double mean = 0;
    for (int k = 0; k < phi_nodes; ++k) {
        const double phi = (pi / 2) * k / (phi_nodes - 1);
        for (int i = 0; i < mu_nodes; ++i) {
            const float mu = detail::albedo_node_mu(i, mu_nodes), s = std::sqrt(1.0f - mu * mu);
            e_[k][i] = float(ggx_directional_albedo(g, vec3f{s * float(std::cos(phi)), s * float(std::sin(phi)), mu}));
        }
        // The mean over azimuths of the mean over cosines, by the trapezoid rule: exact for the
        // interpolant, linear between azimuth nodes.
        mean += detail::cosine_weighted_mean(e_[k], mu_nodes) * ((k == 0 || k == phi_nodes - 1) ? 0.5 : 1.0);
    }
    average_ = float(mean / (phi_nodes - 1));
}

inline float ggx_anisotropic_albedo::albedo(const vec3f& w) const {
    // D and G are even in x and in y: fold the azimuth into [0, pi/2].
    const float phi = std::atan2(std::fabs(w.y), std::fabs(w.x));
    float wp, wm;
    const int k = detail::albedo_cell(phi * float((phi_nodes - 1) / (pi / 2)), phi_nodes, wp);
    const int i = detail::albedo_cell(w.z * (mu_nodes - 1), mu_nodes, wm);
    const float lo = e_[k][i] + wm * (e_[k][i + 1] - e_[k][i]);
    const float hi = e_[k + 1][i] + wm * (e_[k + 1][i + 1] - e_[k + 1][i]);
    return lo + wp * (hi - lo);
}

inline const ggx_albedo_table& ggx_albedo() {
    static const ggx_albedo_table table;
    return table;
}

// The multiple-scattering lobe of Kulla and Conty for a GGX mirror of mean Fresnel reflectance
// f_avg (per channel), given the white mirror's albedos E towards o and i and its mean E_avg:
//   f_ms cos_i = F_ms (1 - E(o)) (1 - E(i)) cos_i / (pi (1 - E_avg)),
// with the colour of light that bounced more than once, F_ms = f_avg^2 E_avg / (1 - f_avg (1 -
// E_avg)) (their slides' "Fresnel of multiple bounces"; 1 for a white mirror).
inline vec3f ggx_multiple_scattering(float e_o, float e_i, float cos_i, float e_avg, const vec3f& f_avg) {
    if (!(e_avg < 1.0f) || !(cos_i > 0)) return {0, 0, 0};
    const float lobe = (1.0f - e_o) * (1.0f - e_i) * cos_i / (pi_f * (1.0f - e_avg));
    auto colour = [&](float f) { return f * f * e_avg / (1.0f - f * (1.0f - e_avg)); };
    return vec3f{colour(f_avg.x), colour(f_avg.y), colour(f_avg.z)} * lobe;
}

} // namespace rt
