#pragma once
// constant_medium: book 2's fog and smoke, a volume of constant density inside a boundary shape.
//
//   auto fog = make_shared<constant_medium>(boundary, 0.01, color(1, 1, 1)); // density, albedo
//   world.add(fog);                                   // the boundary itself need not be added
//
//   constant_medium(boundary, density, albedo)        the phase function is isotropic(albedo)
//   constant_medium(boundary, density, texture)       isotropic(texture)
//   hit(r, ray_t, rec)                                a random scattering point, or none
//   bounding_box()                                    the boundary's
//
// A ray travelling a length L inside the medium scatters there with probability 1 - exp(-density L)
// (Beer-Lambert): hit() draws the free-flight distance -ln(random_double()) / density, the inverse
// of that distribution, walks it along the parts of the ray inside the boundary, and reports a hit
// of the phase function where it runs out (none if the ray leaves first). A ray that starts
// inside counts from its origin. Used as a shadow ray's occluder, that hit is a one-sample
// estimate of the transmittance exp(-density L): unbiased, as a path tracer needs.
//
// The boundary may be any closed surface, convex or not: hit() finds its crossings along the whole
// line of the ray, entering where a crossing is a front face (set_face_normal's outward normal
// against the ray) and leaving where it is a back face, and counts as inside wherever the entries
// outnumber the exits or the exits the entries (the non-zero winding rule). So a torus, a mesh or
// a hittable_list of overlapping boxes (their union) holds fog in every part, where the book's code,
// which takes the first entry and the first exit only, fills the first part a ray crosses and
// misses the rest. A boundary that is not closed has no inside: the fog is where the crossings
// found say it is.
//
// In the renderer the medium is a user-written shape in the BVH (scene/user_shape_set.h), called
// through this hit() with random_double() drawing from the sample's own generator; its isotropic
// phase function is a built-in material of the contract (core/bsdf.h), so next-event estimation
// and multiple importance sampling work at every scattering point inside the fog.

#include "color.h"
#include "core/recognise.h"
#include "hittable.h"
#include "interval.h"
#include "material.h"
#include "ray.h"
#include "core/scene_error.h"
#include "sphere.h"
#include "texture.h"
#include "vec3.h"

#include <cmath>
#include <limits>
#include <memory>
#include <string>

namespace rt {

class constant_medium : public hittable {
  public:
    // Throws scene_error for a null boundary or texture or a density that is negative or not finite.
    constant_medium(std::shared_ptr<hittable> boundary, double density, std::shared_ptr<texture> tex);
    constant_medium(std::shared_ptr<hittable> boundary, double density, const color& albedo);

    bool hit(const ray& r, interval ray_t, hit_record& rec) const override;
    aabb bounding_box() const override { return boundary_->bounding_box(); }

    const std::shared_ptr<hittable>& boundary() const { return boundary_; }
    double density() const { return density_; }
    const std::shared_ptr<material>& phase_function() const { return phase_function_; }

    // Where a ray scatters in the chord [enter, leave] of its line through a medium of `density`,
    // cut to ray_t: one free-flight draw, taken only when the cut chord is not empty (as the
    // crossing walk in hit() draws), and rec filled at that distance (scattering_point). False
    // when the ray gets through. The closed forms (a sphere's chord here, convex_medium's) share
    // it, so that they draw as hit() does. ray_length is |r.direction()|.
    static bool scatter_in_chord(const ray& r, double ray_length, double enter, double leave, interval ray_t,
                                 double density, const std::shared_ptr<material>& phase, hit_record& rec) {
        const double from = std::fmax(enter, ray_t.min), to = std::fmin(leave, ray_t.max);
        if (!(from < to)) return false;
        const double distance = -std::log(random_double()) / density;
        if (!(distance < (to - from) * ray_length)) return false;
        scattering_point(r, from + distance / ray_length, phase, rec);
        return true;
    }

    // Fills rec with the scattering point at r.at(t): of the phase function, with no surface
    // (the normal is arbitrary, the face the front one, no texture coordinates).
    static void scattering_point(const ray& r, double t, const std::shared_ptr<material>& phase, hit_record& rec) {
        rec.t = t;
        rec.p = r.at(t);
        rec.normal = vec3(1, 0, 0);
        rec.front_face = true;
        rec.u = rec.v = 0;
        rec.mat = phase;
    }

  private:
    std::shared_ptr<hittable> boundary_;
    const sphere* boundary_sphere_ = nullptr; // the boundary, when it is exactly a sphere
    double density_;
    std::shared_ptr<material> phase_function_;
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline constant_medium::constant_medium(std::shared_ptr<hittable> boundary, double density,
                                        std::shared_ptr<texture> tex)
    : boundary_(std::move(boundary)), density_(density) {
    if (!boundary_) throw scene_error("constant_medium boundary is null");
    if (!tex) throw scene_error("constant_medium texture is null");
    if (!(std::isfinite(density) && density >= 0))
        throw scene_error("constant_medium density must be finite and non-negative, got " + number_text(density));
    phase_function_ = std::make_shared<isotropic>(std::move(tex));
    if (is_exactly<sphere>(*boundary_)) boundary_sphere_ = static_cast<const sphere*>(boundary_.get());
}

inline constant_medium::constant_medium(std::shared_ptr<hittable> boundary, double density, const color& albedo)
    : constant_medium(std::move(boundary), density, std::make_shared<solid_color>(albedo)) {}

inline bool constant_medium::hit(const ray& r, interval ray_t, hit_record& rec) const {
    const double ray_length = r.direction().length();
    if (!(ray_length > 0) || !(density_ > 0) || !(ray_t.min < ray_t.max)) return false;
    const double infinity = std::numeric_limits<double>::infinity(), origin_size = r.origin().length();
    // The next crossing is looked for a little past the last one, so that rounding cannot find the
    // same one again: 1e-9 of the magnitudes of the coordinates, far below any feature size and
    // far above double's rounding of a hit.
    auto past = [&](double t) {
        return std::isinf(t) ? t : t + 1e-9 * (1 + origin_size + std::fabs(t) * ray_length) / ray_length;
    };
    // A sphere (the book's usual boundary): its one chord in closed form, without asking the
    // boundary's hit() for hit records (whose shared material pointers, copied on every call,
    // make threads contend for one reference count). The same draws and the same answer.
    if (boundary_sphere_) {
        double t0, t1;
        const sphere& s = *boundary_sphere_;
        if (!sphere_roots(r.origin(), r.direction(), s.center(r.time()), s.radius(), t0, t1)) return false;
        return scatter_in_chord(r, ray_length, t0, t1, ray_t, density_, phase_function_, rec);
    }
    double distance_left = -1; // the free-flight distance still to go inside; drawn at first need
    double t = -infinity;      // the last crossing: from the start of the ray's line
    int winding = 0;           // entries minus exits before t
    hit_record crossing;
    while (boundary_->hit(r, interval(past(t), infinity), crossing)) {
        // Inside on (t, crossing.t): the part of it within ray_t uses up free-flight distance.
        const double from = std::fmax(t, ray_t.min), to = std::fmin(crossing.t, ray_t.max);
        if (winding != 0 && from < to) {
            if (distance_left < 0) distance_left = -std::log(random_double()) / density_;
            const double inside = (to - from) * ray_length;
            if (distance_left < inside) {
                scattering_point(r, from + distance_left / ray_length, phase_function_, rec);
                return true;
            }
            distance_left -= inside;
        }
        if (crossing.t >= ray_t.max) return false;
        winding += crossing.front_face ? 1 : -1;
        t = crossing.t;
    }
    return false;
}

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::constant_medium;
#endif
