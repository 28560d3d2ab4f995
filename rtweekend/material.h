#pragma once
// material: how a surface scatters and emits light (the books' interface), and the books'
// materials:
//   lambertian(albedo)           ideal diffuse; lambertian(texture) for a colour that varies
//                                over the surface (book 2)
//   metal(albedo, fuzz)          mirror reflection, its direction moved by a uniform random point
//                                in a ball of radius fuzz (<= 1)
//   dielectric(refraction_index) glass: reflects or refracts, chosen by Schlick's approximation
//   diffuse_light(emit)          an emitter (books 2 and 3): emits `emit` from its front face
//                                only (book 3), or from both with diffuse_light(emit, true) (book 2)
// and two beyond the books, with the exact Fresnel equations (core/fresnel.h):
//   conductor(n, k, tint)        a smooth metal of complex index n + ik: mirror reflection
//                                weighted by tint * Fr(cos); n, k scalars or per-channel colours
//   dielectric(refraction_index, absorption)
//                                glass that reflects with the exact Fresnel probability and,
//                                inside, keeps exp(-absorption * distance) per channel (Beer's law)
// book 2's phase function, for constant_medium (constant_medium.h):
//   isotropic(albedo)            scatters uniformly over all directions; isotropic(texture) too
// and two glossy surfaces, with a density that light sampling can weigh (formulas in core/materials/):
//   plastic(diffuse, refraction_index = 1.5)
//                                a Lambertian base under a smooth clear coat: the coat's mirror
//                                reflection, Fresnel-weighted, over the base; a white plastic
//                                reflects everything it receives
//   blinn_phong(diffuse, specular, exponent)
//                                a Lambertian lobe plus a normalised Blinn-Phong glossy lobe (the
//                                CENG795 course's surface); diffuse + specular is scaled down to 1
//                                per channel where it exceeds it, so no energy is created
//
// Each material's physics is written once, in the renderer's material contract (core/bsdf.h:
// sample, eval, pdf; one header a kind in core/materials/), which every integrator calls. The renderer recognises these classes and
// calls the contract directly, without virtual calls. The virtual functions below are the books'
// interface, for code that calls them itself (a ray_color of one's own); for the built-in
// materials they draw from the same contract, in float (directions and weights agree with double
// arithmetic to about 1e-6), with random_double(). A user's own material subclass overrides them,
// and the renderer calls it.
//
// The books' three generations of the interface live side by side:
//   book 1   scatter(r_in, rec, attenuation, scattered)
//   book 2   emitted(u, v, p)
//   book 3   scatter(r_in, rec, srec), scattering_pdf(r_in, rec, scattered),
//            emitted(r_in, rec, u, v, p)
// By default each later form calls the earlier one: a book-1 material's scatter is reported to
// book-3 code as a ray that skips the pdf (srec.skip_pdf, as the book's metal and glass do), and a
// book-2 light emits through book 3's emitted. A class that overrides one form of a name brings
// the other into scope (`using material::scatter;`), so it is not hidden.

#include "color.h"
#include "core/engine_linkage.h"
#include "core/material_kinds.h"
#include "core/rng.h"
#include "core/vec3f.h"
#include "hittable.h"
#include "pdf.h"
#include "ray.h"
#include "texture.h"

#include <cmath>
#include <memory>

namespace rt {

// What book 3's scatter() reports: the attenuation, and either a pdf to draw the next direction
// from (weighed by scattering_pdf) or, when skip_pdf is set, the one ray to follow (mirrors, glass).
class scatter_record {
  public:
    color attenuation;
    std::shared_ptr<pdf> pdf_ptr;
    bool skip_pdf = false;
    ray skip_pdf_ray;
};

class material {
  public:
    virtual ~material() = default;

    // Book 2: light emitted at surface coordinates (u, v), point p. None by default.
    virtual color emitted(double /*u*/, double /*v*/, const point3& /*p*/) const { return color(0, 0, 0); }

    // Book 3: the same, knowing the ray and the hit (a one-sided light looks at rec.front_face).
    // By default, the book-2 form.
    virtual color emitted(const ray& /*r_in*/, const hit_record& /*rec*/, double u, double v, const point3& p) const {
        return emitted(u, v, p);
    }

    // Book 1: whether the ray scatters; if so, the scattered ray and its attenuation.
    virtual bool scatter(const ray& /*r_in*/, const hit_record& /*rec*/, color& /*attenuation*/,
                         ray& /*scattered*/) const {
        return false;
    }

    // Book 3: whether the ray scatters; if so, srec. By default, the book-1 scatter's ray,
    // reported as one to follow without a pdf: a book-1 material works unchanged under book-3
    // code and under the renderer.
    virtual bool scatter(const ray& r_in, const hit_record& rec, scatter_record& srec) const {
        srec.pdf_ptr = nullptr;
        srec.skip_pdf = true;
        return scatter(r_in, rec, srec.attenuation, srec.skip_pdf_ray);
    }

    // Book 3: the density with which the surface scatters r_in into `scattered` (the BRDF times
    // the cosine, per solid angle). 0 for materials without one (mirrors, glass, lights).
    virtual double scattering_pdf(const ray& /*r_in*/, const hit_record& /*rec*/, const ray& /*scattered*/) const {
        return 0;
    }
};

namespace detail {

// random_double() as the contract draws its numbers: uniform in [0, 1) in float.
struct book_uniform {
    float next_float() {
        float u = static_cast<float>(random_double());
        return u < 1.0f ? u : 0x1.fffffep-1f; // a double just below 1 rounds up to 1 in float
    }
};

// The book's scatter() through the material contract: one draw of `m`'s sample() at the hit, in
// world coordinates. A ray that reaches the back face of absorbing glass has travelled
// rec.t * |direction| inside it: its weight includes Beer's law for that distance, as the path
// tracer's does.
RTWEEKEND_ENGINE_FUNCTION bool scatter_through_contract(const compiled_material& m, const ray& r_in,
                                                        const hit_record& rec, color& attenuation, ray& scattered);

// Left out of a program that links the engine (core/engine_linkage.h): the draw instantiates
// every material kind's sample().
#if RTWEEKEND_ENGINE_BODIES
RTWEEKEND_ENGINE_FUNCTION bool scatter_through_contract(const compiled_material& m, const ray& r_in,
                                                        const hit_record& rec, color& attenuation, ray& scattered) {
    const shading_point sp{vec3f(rec.normal), rec.front_face};
    book_uniform u;
    material_sample s;
    if (!m.sample(-normalize(vec3f(r_in.direction())), sp, u, s)) return false;
    vec3f weight = s.value;
    if (!rec.front_face && m.absorbs_inside())
        weight *= m.transmittance(static_cast<float>(rec.t * r_in.direction().length()));
    attenuation = weight.to_double();
    scattered = ray(rec.p, s.wi.to_double());
    return true;
}
#endif

} // namespace detail

// A colour that may vary over a surface, as book 2's materials take it: a texture, and its one
// colour when the texture is exactly a solid_color (what the renderer then uses without asking
// the texture). Held by lambertian and isotropic.
class surface_colour {
  public:
    surface_colour(const color& c) : tex_(std::make_shared<solid_color>(c)), constant_(c), solid_(true) {}
    surface_colour(std::shared_ptr<texture> tex) : tex_(std::move(tex)) {
        if (const solid_color* solid = exact_solid_color(tex_.get())) {
            constant_ = solid->albedo();
            solid_ = true;
        }
    }

    color at(const hit_record& rec) const { return tex_->value(rec.u, rec.v, rec.p); }
    // The colour when the texture is a solid_color; black for any other texture.
    const color& constant() const { return constant_; }
    bool solid() const { return solid_; }
    const std::shared_ptr<texture>& tex() const { return tex_; }

  private:
    std::shared_ptr<texture> tex_;
    color constant_{0, 0, 0};
    bool solid_ = false;
};

class lambertian : public material {
  public:
    lambertian(const color& albedo) : albedo_(albedo) {}
    // Book 2: a textured surface, its albedo looked up at the hit's (u, v) and point.
    lambertian(std::shared_ptr<texture> tex) : albedo_(std::move(tex)) {}

    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        compiled_material m = compiled();
        if (!albedo_.solid()) m = m.with_colour(vec3f(albedo_.at(rec)));
        return detail::scatter_through_contract(m, r_in, rec, attenuation, scattered);
    }

    // Book 3: cosine-weighted about the normal; the renderer's draw is the same density.
    bool scatter(const ray& /*r_in*/, const hit_record& rec, scatter_record& srec) const override {
        srec.attenuation = albedo_.at(rec);
        srec.pdf_ptr = std::make_shared<cosine_pdf>(rec.normal);
        srec.skip_pdf = false;
        return true;
    }

    double scattering_pdf(const ray& /*r_in*/, const hit_record& rec, const ray& scattered) const override {
        double cos_theta = dot(rec.normal, unit_vector(scattered.direction()));
        return cos_theta < 0 ? 0 : cos_theta / pi;
    }

    // The material as the renderer's contract sees it (unchecked: material_compiler.h checks).
    // For a texture other than a solid_color the scene compiler adds the texture's index into
    // the scene's texture table (scene/texture_table.h); the albedo is looked up per hit.
    compiled_material compiled() const { return compiled_material::of(lambertian_bsdf{vec3f(albedo_.constant())}, this); }

    // The albedo when the texture is a solid_color; black for any other texture.
    const color& albedo() const { return albedo_.constant(); }
    const std::shared_ptr<texture>& tex() const { return albedo_.tex(); }

  private:
    surface_colour albedo_;
};

class metal : public material {
  public:
    // Fuzz above 1 is clamped to 1, as in the book; NaN is kept so the renderer can reject it.
    // The fuzz offset is a point inside the ball (as the book's edition that rendered the team's
    // reference images has it); later editions moved it onto the sphere's surface, which blurs
    // reflections a little more.
    metal(const color& albedo, double fuzz) : albedo_(albedo), fuzz_(fuzz > 1 ? 1 : fuzz) {}

    // Book 3's scatter(r_in, rec, srec) is material's: this draw, as a ray that skips the pdf.
    using material::scatter;
    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        return detail::scatter_through_contract(compiled(), r_in, rec, attenuation, scattered);
    }

    compiled_material compiled() const {
        return compiled_material::of(metal_bsdf{vec3f(albedo_), static_cast<float>(fuzz_)}, this);
    }

    const color& albedo() const { return albedo_; }
    double fuzz() const { return fuzz_; }

  private:
    color albedo_;
    double fuzz_;
};

class dielectric : public material {
  public:
    // The book's glass: Schlick's reflectance, no absorption.
    dielectric(double refraction_index) : refraction_index_(refraction_index) {}

    // Glass with the exact Fresnel reflectance and Beer's law: light that travels a distance d
    // inside keeps exp(-absorption * d) of itself, per channel (absorption per unit length;
    // 0 0 0 is clear glass).
    dielectric(double refraction_index, const color& absorption)
        : refraction_index_(refraction_index), absorption_(absorption), exact_fresnel_(true) {}

    // Book 3's scatter(r_in, rec, srec) is material's: this draw, as a ray that skips the pdf.
    using material::scatter;
    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        return detail::scatter_through_contract(compiled(), r_in, rec, attenuation, scattered);
    }

    compiled_material compiled() const {
        const float ri = static_cast<float>(refraction_index_);
        if (exact_fresnel_) return compiled_material::of(fresnel_glass_bsdf{ri, vec3f(absorption_)}, this);
        return compiled_material::of(dielectric_bsdf{ri}, this);
    }

    // Refractive index in vacuum or air, or the ratio of the material's refractive index over
    // the refractive index of the enclosing media.
    double refraction_index() const { return refraction_index_; }
    const color& absorption() const { return absorption_; }
    // True for the two-argument constructor: exact Fresnel and Beer's law instead of Schlick.
    bool exact_fresnel() const { return exact_fresnel_; }

  private:
    double refraction_index_;
    color absorption_{0, 0, 0};
    bool exact_fresnel_ = false;
};

// A smooth conductor (metal) of complex refractive index n + ik, seen from air: a perfect mirror
// whose reflectance is the exact Fresnel reflectance Fr(cos, n, k) per channel, times `tint` (an
// artist's control; 1 1 1 is the physical metal). Per-channel n and k give coloured metals:
// gold is roughly n = (0.18, 0.42, 1.37), k = (3.42, 2.35, 1.77) at 650, 550, 450 nm.
class conductor : public material {
  public:
    conductor(double n, double k, const color& tint) : conductor(color(n, n, n), color(k, k, k), tint) {}
    conductor(const color& n, const color& k, const color& tint) : n_(n), k_(k), tint_(tint) {}

    // Book 3's scatter(r_in, rec, srec) is material's: this draw, as a ray that skips the pdf.
    using material::scatter;
    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        return detail::scatter_through_contract(compiled(), r_in, rec, attenuation, scattered);
    }

    compiled_material compiled() const {
        return compiled_material::of(conductor_bsdf{vec3f(tint_), vec3f(n_), vec3f(k_)}, this);
    }

    const color& n() const { return n_; }
    const color& k() const { return k_; }
    const color& tint() const { return tint_; }

  private:
    color n_, k_, tint_;
};

// Rough materials: GGX microfacets (core/microfacet.h). A roughness is in [0, 1]: 0 is smooth (a
// mirror, clear glass), 1 is as rough as GGX goes; the microfacet slope alpha is roughness^2, as in
// glTF and Disney's model. Two roughnesses give an anisotropic surface: roughness_u along the
// direction around the world's y axis, roughness_v across it (a turned or brushed finish).

// A rough metal (core/materials/rough_conductor_bsdf.h). With an albedo: the reflectance at
// normal incidence, whitening towards grazing by Schlick's approximation (the form glTF's metals
// and most asset libraries give). With a complex index n + ik per channel: the exact Fresnel
// reflectance, as conductor. The light single scattering between microfacets loses is returned
// (Kulla and Conty 2017), so a white rough conductor reflects everything at every roughness.
class rough_conductor : public material {
  public:
    rough_conductor(const color& albedo, double roughness) : rough_conductor(albedo, roughness, roughness) {}
    rough_conductor(const color& albedo, double roughness_u, double roughness_v)
        : albedo_(albedo), roughness_u_(roughness_u), roughness_v_(roughness_v), data_(make_data(false)) {}
    rough_conductor(const color& n, const color& k, double roughness) : rough_conductor(n, k, roughness, roughness) {}
    rough_conductor(const color& n, const color& k, double roughness_u, double roughness_v)
        : n_(n), k_(k), roughness_u_(roughness_u), roughness_v_(roughness_v), data_(make_data(true)) {}

    using material::scatter;
    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        return detail::scatter_through_contract(compiled(), r_in, rec, attenuation, scattered);
    }

    compiled_material compiled() const {
        rough_conductor_bsdf b;
        b.distribution = distribution();
        b.f0 = vec3f(albedo_);
        b.data = data_.get();
        return compiled_material::of(b, this);
    }

    bool complex_index() const { return data_->complex_index; }
    const color& albedo() const { return albedo_; }
    const color& n() const { return n_; }
    const color& k() const { return k_; }
    double roughness_u() const { return roughness_u_; }
    double roughness_v() const { return roughness_v_; }

  private:
    color albedo_{1, 1, 1}, n_{1, 1, 1}, k_{0, 0, 0};
    double roughness_u_, roughness_v_;
    // Worked out once, when the material is made: the mean Fresnel reflectance of a complex
    // index (256 evaluations per channel) and an anisotropic surface's albedo table (some 20 ms;
    // not for roughnesses outside [0, 1], which compile_material refuses).
    std::shared_ptr<const rough_conductor_data> data_;

    ggx distribution() const { return {alpha_of_roughness(float(roughness_u_)), alpha_of_roughness(float(roughness_v_))}; }
    std::shared_ptr<const rough_conductor_data> make_data(bool complex_index) const {
        auto d = std::make_shared<rough_conductor_data>();
        d->complex_index = complex_index;
        if (complex_index) {
            d->eta = vec3f(n_);
            d->k = vec3f(k_);
            d->fresnel_average = conductor_fresnel_average(d->eta, d->k);
        }
        const ggx g = distribution();
        const bool in_range = roughness_u_ >= 0 && roughness_u_ <= 1 && roughness_v_ >= 0 && roughness_v_ <= 1;
        if (in_range && !g.isotropic() && !g.smooth()) d->anisotropic.emplace(g);
        return d;
    }
};

// Rough glass of refractive index `refraction_index` (core/materials/rough_dielectric_bsdf.h):
// frosted, etched or ground glass; it reflects and refracts through GGX microfacets with the
// exact Fresnel reflectance. At roughness 0 it is dielectric(refraction_index, color(0, 0, 0)).
class rough_dielectric : public material {
  public:
    rough_dielectric(double refraction_index, double roughness)
        : rough_dielectric(refraction_index, roughness, roughness) {}
    rough_dielectric(double refraction_index, double roughness_u, double roughness_v)
        : refraction_index_(refraction_index), roughness_u_(roughness_u), roughness_v_(roughness_v) {}

    using material::scatter;
    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        return detail::scatter_through_contract(compiled(), r_in, rec, attenuation, scattered);
    }

    compiled_material compiled() const {
        rough_dielectric_bsdf b;
        b.refraction_index = static_cast<float>(refraction_index_);
        b.distribution = {alpha_of_roughness(float(roughness_u_)), alpha_of_roughness(float(roughness_v_))};
        return compiled_material::of(b, this);
    }

    double refraction_index() const { return refraction_index_; }
    double roughness_u() const { return roughness_u_; }
    double roughness_v() const { return roughness_v_; }

  private:
    double refraction_index_, roughness_u_, roughness_v_;
};

// glTF 2.0's metallic-roughness material (core/materials/metal_rough_bsdf.h): metallic 1 is a
// rough metal of colour base_colour, metallic 0 a diffuse base of that colour under a clear coat
// of index 1.5; values between blend the two.
class metal_roughness : public material {
  public:
    metal_roughness(const color& base_colour, double metallic, double roughness)
        : base_colour_(base_colour), metallic_(metallic), roughness_(roughness) {}
    // The base colour looked up per hit, as lambertian's albedo is (glTF's baseColorTexture).
    metal_roughness(std::shared_ptr<texture> base_colour, double metallic, double roughness)
        : base_colour_(std::move(base_colour)), metallic_(metallic), roughness_(roughness) {}
    // And metallic and roughness per hit too, as glTF's metallicRoughnessTexture gives them: the
    // map's blue channel times `metallic`, its green times `roughness` (read as data, not colour:
    // rtw_image::as_data), each clamped to [0, 1]. A null map: the factors alone.
    metal_roughness(std::shared_ptr<texture> base_colour, double metallic, double roughness,
                    std::shared_ptr<texture> metallic_roughness_map)
        : base_colour_(std::move(base_colour)), metallic_(metallic), roughness_(roughness),
          map_(std::move(metallic_roughness_map)) {}

    using material::scatter;
    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        compiled_material m = compiled();
        if (!base_colour_.solid()) m = m.with_colour(vec3f(base_colour_.at(rec)));
        if (map_) {
            const color t = map_->value(rec.u, rec.v, rec.p);
            m.edit<metal_rough_bsdf>([&](metal_rough_bsdf& b) {
                b.set_metallic_roughness(float(metallic_ * t.z()), float(roughness_ * t.y()));
            });
        }
        return detail::scatter_through_contract(m, r_in, rec, attenuation, scattered);
    }

    // For a texture other than a solid_color the scene compiler adds it to the scene's texture
    // table, as for lambertian.
    compiled_material compiled() const {
        metal_rough_bsdf b;
        b.base_colour = vec3f(base_colour_.constant());
        b.set_metallic_roughness(float(metallic_), float(roughness_));
        return compiled_material::of(b, this);
    }

    // The base colour when the texture is a solid_color; black for any other texture.
    const color& base_colour() const { return base_colour_.constant(); }
    const std::shared_ptr<texture>& tex() const { return base_colour_.tex(); }
    double metallic() const { return metallic_; }
    double roughness() const { return roughness_; }
    const std::shared_ptr<texture>& metallic_roughness_map() const { return map_; }

  private:
    surface_colour base_colour_;
    double metallic_, roughness_;
    std::shared_ptr<texture> map_;
};

// A material with a tangent-space normal map (glTF's normalTexture): the texture's colour c at the
// hit, read as the normal n = 2 c - 1 in the frame of the surface's dp/du, dp/dv and normal (x and
// y times `scale`), replaces the shading normal, so that a flat triangle shades as the detail the
// map holds. The map holds data, not colour: read its picture with rtw_image::as_data(). The
// renderer applies it on triangles with texture coordinates (scene/surface_coordinates.h:
// shading_normal_at); the book's scatter() and emitted() are the base material's, unperturbed.
//
//   auto bumpy = make_shared<normal_mapped>(make_shared<metal_roughness>(gold, 1.0, 0.3), normals);
class normal_mapped : public material {
  public:
    normal_mapped(std::shared_ptr<material> base, std::shared_ptr<texture> normals, double scale = 1)
        : base_(std::move(base)), normals_(std::move(normals)), scale_(scale) {}

    color emitted(double u, double v, const point3& p) const override { return base_->emitted(u, v, p); }
    color emitted(const ray& r_in, const hit_record& rec, double u, double v, const point3& p) const override {
        return base_->emitted(r_in, rec, u, v, p);
    }
    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        return base_->scatter(r_in, rec, attenuation, scattered);
    }
    bool scatter(const ray& r_in, const hit_record& rec, scatter_record& srec) const override {
        return base_->scatter(r_in, rec, srec);
    }
    double scattering_pdf(const ray& r_in, const hit_record& rec, const ray& scattered) const override {
        return base_->scattering_pdf(r_in, rec, scattered);
    }

    const std::shared_ptr<material>& base() const { return base_; }
    const std::shared_ptr<texture>& normals() const { return normals_; }
    double scale() const { return scale_; }
    // Whether the texture holds heights (bump_mapped, below) rather than normals.
    bool holds_heights() const { return heights_; }

  protected:
    normal_mapped(std::shared_ptr<material> base, std::shared_ptr<texture> map, double scale, bool heights)
        : base_(std::move(base)), normals_(std::move(map)), scale_(scale), heights_(heights) {}

  private:
    std::shared_ptr<material> base_;
    std::shared_ptr<texture> normals_;
    double scale_;
    bool heights_ = false;
};

// A material with a bump (height) map (an OBJ's `bump`): the texture's mean channel h at (u, v),
// as data, times `scale` is a displacement along the normal in world units, d = scale h (as
// pbrt's bump mapping and Blender's Bump node at distance 1 read one). The shading normal becomes
// the normal of the displaced surface, cross(dp/du + dd/du N, dp/dv + dd/dv N) (Blinn 1978,
// without the small dN/du terms), the slopes dd/du, dd/dv taken by central differences 1e-4 apart
// in (u, v). Like normal_mapped, it applies on triangles with texture coordinates.
//
//   auto rough_wall = make_shared<bump_mapped>(make_shared<lambertian>(grey), heights, 0.02);
class bump_mapped : public normal_mapped {
  public:
    bump_mapped(std::shared_ptr<material> base, std::shared_ptr<texture> heights, double scale)
        : normal_mapped(std::move(base), std::move(heights), scale, true) {}
};

// An emitter (books 2 and 3). Book 3's light emits from its front face only (the side its
// shape's normal points to: a quad's cross(u, v)); book 2's from both, which two_sided = true
// keeps. It scatters nothing (material's scatter() defaults).
class diffuse_light : public material {
  public:
    diffuse_light(std::shared_ptr<texture> tex) : diffuse_light(std::move(tex), false) {}
    diffuse_light(const color& emit) : diffuse_light(emit, false) {}
    // Beyond the books: the choice of faces.
    diffuse_light(const color& emit, bool two_sided)
        : tex_(std::make_shared<solid_color>(emit)), emission_(emit), two_sided_(two_sided) {}
    diffuse_light(std::shared_ptr<texture> tex, bool two_sided) : tex_(std::move(tex)), two_sided_(two_sided) {
        if (const solid_color* solid = exact_solid_color(tex_.get())) emission_ = solid->albedo();
    }

    // Book 2: the texture's radiance (this form has no hit to tell the faces apart).
    color emitted(double u, double v, const point3& p) const override { return tex_->value(u, v, p); }

    // Book 3: nothing from the back face unless two-sided.
    color emitted(const ray& /*r_in*/, const hit_record& rec, double u, double v, const point3& p) const override {
        if (!rec.front_face && !two_sided_) return color(0, 0, 0);
        return emitted(u, v, p);
    }

    // The material as the renderer's contract sees it (unchecked: material_compiler.h checks).
    // Complete only when the texture is a solid_color.
    compiled_material compiled() const { return compiled_material::of(emitter_bsdf{vec3f(emission_), two_sided_}, this); }

    // The emitted radiance when the texture is a solid_color; black for any other texture.
    const color& emission() const { return emission_; }
    bool two_sided() const { return two_sided_; }
    const std::shared_ptr<texture>& tex() const { return tex_; }

  private:
    std::shared_ptr<texture> tex_;
    color emission_{0, 0, 0};
    bool two_sided_ = false;
};

// Book 2's phase function: light scattered at a point of a constant_medium leaves in a uniformly
// random direction, attenuated by the albedo. A material like any other: on a surface it scatters
// to both sides alike.
class isotropic : public material {
  public:
    isotropic(const color& albedo) : albedo_(albedo) {}
    isotropic(std::shared_ptr<texture> tex) : albedo_(std::move(tex)) {}

    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        compiled_material m = compiled();
        if (!albedo_.solid()) m = m.with_colour(vec3f(albedo_.at(rec)));
        return detail::scatter_through_contract(m, r_in, rec, attenuation, scattered);
    }

    // Book 3: uniform over the sphere of directions, density 1 / (4 pi).
    bool scatter(const ray& /*r_in*/, const hit_record& rec, scatter_record& srec) const override {
        srec.attenuation = albedo_.at(rec);
        srec.pdf_ptr = std::make_shared<sphere_pdf>();
        srec.skip_pdf = false;
        return true;
    }

    double scattering_pdf(const ray& /*r_in*/, const hit_record& /*rec*/, const ray& /*scattered*/) const override {
        return 1 / (4 * pi);
    }

    // Complete only when the texture is a solid_color; any other texture is rendered through the
    // virtual functions above (the medium reports the material at its own hit, which the texture
    // table does not reach).
    compiled_material compiled() const { return compiled_material::of(isotropic_phase{vec3f(albedo_.constant())}, this); }

    const color& albedo() const { return albedo_.constant(); }
    const std::shared_ptr<texture>& tex() const { return albedo_.tex(); }

  private:
    surface_colour albedo_;
};

// A diffuse base of colour `diffuse` under a smooth dielectric coat of index refraction_index (in
// air): the coat mirrors F(cos) of the light (Fresnel), the base returns diffuse (1 - F(cos)) of it
// (core/materials/plastic_bsdf.h, plastic_base_factor). Varnished wood, plastic toys, glazed pottery.
class plastic : public material {
  public:
    plastic(const color& diffuse, double refraction_index = 1.5)
        : diffuse_(diffuse), refraction_index_(refraction_index),
          coat_average_(std::isfinite(refraction_index) && refraction_index > 0 ? fresnel_average(refraction_index) : 0) {}

    using material::scatter;
    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        return detail::scatter_through_contract(compiled(), r_in, rec, attenuation, scattered);
    }

    compiled_material compiled() const {
        return compiled_material::of(
            plastic_bsdf{vec3f(diffuse_), static_cast<float>(refraction_index_), static_cast<float>(coat_average_)}, this);
    }

    const color& diffuse() const { return diffuse_; }
    double refraction_index() const { return refraction_index_; }

  private:
    color diffuse_;
    double refraction_index_;
    double coat_average_; // the coat's mean reflectance of diffuse light, computed once
};

// Lambertian reflectance `diffuse` plus a glossy Blinn-Phong lobe of reflectance `specular` and
// Phong exponent `exponent` (higher: sharper highlights), normalised so that it never reflects
// more than `specular` (core/materials/blinn_phong_bsdf.h, blinn_phong_lobe). Where diffuse + specular exceeds 1 in a
// channel both are scaled by 1 / (diffuse + specular) there, so the surface creates no energy.
class blinn_phong : public material {
  public:
    blinn_phong(const color& diffuse, const color& specular, double exponent)
        : diffuse_(diffuse), specular_(specular), exponent_(exponent) {}

    using material::scatter;
    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        return detail::scatter_through_contract(compiled(), r_in, rec, attenuation, scattered);
    }

    compiled_material compiled() const { return contract(diffuse_, specular_, exponent_, this); }

    // The contract's entry for these parameters, scaled down to conserve energy (also used by
    // whitted_material for the course's Blinn-Phong surfaces).
    static compiled_material contract(const color& diffuse, const color& specular, double exponent,
                                      const material* source) {
        const color sum = diffuse + specular;
        const color scale(sum.x() > 1 ? 1 / sum.x() : 1, sum.y() > 1 ? 1 / sum.y() : 1, sum.z() > 1 ? 1 / sum.z() : 1);
        return compiled_material::of(
            blinn_phong_bsdf{vec3f(diffuse * scale), vec3f(specular * scale), static_cast<float>(exponent)}, source);
    }

    const color& diffuse() const { return diffuse_; }
    const color& specular() const { return specular_; }
    double exponent() const { return exponent_; }

  private:
    color diffuse_, specular_;
    double exponent_;
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::conductor;
using rt::dielectric;
using rt::diffuse_light;
using rt::blinn_phong;
using rt::isotropic;
using rt::lambertian;
using rt::material;
using rt::metal;
using rt::plastic;
using rt::metal_roughness;
using rt::normal_mapped;
using rt::bump_mapped;
using rt::rough_conductor;
using rt::rough_dielectric;
using rt::scatter_record;
#endif
