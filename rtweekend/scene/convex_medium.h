#pragma once
// convex_medium: the renderer's form of a constant_medium whose boundary is a closed convex
// solid of quads, such as book 2's box() turned by rotate_y and moved by translate (its Cornell
// box of smoke). The scene compiler puts it in the BVH in the medium's place (the user's medium
// is left as it is).
//
//   std::shared_ptr<hittable> fast = convex_medium::make(medium, faces); // null: not convex and closed
//
// constant_medium::hit walks the boundary's crossings one hit() at a time (for a box, three
// passes over six quads through the transforms, each copying a hit record), since a boundary
// may be any closed surface. Inside a convex solid the inside part of a ray's line is one
// interval, [the last entry, the first exit] over the faces' planes (Cyrus and Beck 1978), so
// here it is found in one pass over the planes, in world coordinates. The free-flight distance
// is drawn as constant_medium::hit draws it (one random_double(), only when the ray's interval
// meets the inside), and the scattering point is the same: the image is the same up to the
// rounding of the crossings, and what a ray grazing an edge between two quads sees (the quads
// might leave a crack there; the planes do not).
//
// The faces must bound a convex solid: each face's plane has every corner of every face on one
// side of it, and the quads close up (every edge is an edge of exactly one other quad, to a
// tolerance of 1e-9 of the solid's size). Anything else (a non-convex or open boundary, a
// degenerate quad, more than max_faces faces) gets null, and the medium keeps its own hit().

#include "../aabb.h"
#include "../constant_medium.h"
#include "../hittable.h"
#include "../interval.h"
#include "../ray.h"
#include "../vec3.h"

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

namespace rt {

class convex_medium : public hittable {
  public:
    // A face of the boundary in world coordinates: the parallelogram corner + a u + b v, a and b
    // in [0, 1] (a quad's).
    struct face {
        point3 corner;
        vec3 u, v;
    };
    static constexpr size_t max_faces = 64; // the checks below are quadratic in the faces

    static std::shared_ptr<convex_medium> make(const constant_medium& medium, const std::vector<face>& faces);

    bool hit(const ray& r, interval ray_t, hit_record& rec) const override;
    aabb bounding_box() const override { return box_; }

  private:
    struct plane {
        vec3 n;   // unit, outwards
        double d; // inside: dot(n, x) <= d
    };
    std::vector<plane> planes_;
    double density_ = 0;
    // The medium's phase function: owned once here (phase_owner_), and handed to the hit records
    // through a pointer without a reference count, since copying a counted pointer into every
    // record would make the render's threads contend for one counter.
    std::shared_ptr<material> phase_owner_;
    std::shared_ptr<material> phase_function_;
    aabb box_;
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline std::shared_ptr<convex_medium> convex_medium::make(const constant_medium& medium, const std::vector<face>& faces) {
    if (faces.size() < 4 || faces.size() > max_faces || !medium.phase_function()) return nullptr;
    // The corners, and the solid's size for the tolerance.
    std::vector<point3> corners;
    for (const face& f : faces)
        for (const point3& p : {f.corner, f.corner + f.u, f.corner + f.u + f.v, f.corner + f.v}) {
            if (!(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()))) return nullptr;
            corners.push_back(p);
        }
    double size = 0;
    for (const point3& p : corners) size = std::fmax(size, (p - corners[0]).length());
    if (!(size > 0)) return nullptr;
    const double tolerance = 1e-9 * size;

    auto result = std::make_shared<convex_medium>();
    // Each face's plane, turned to face away from the corners: convex when every corner lies on
    // one side of every face's plane.
    for (const face& f : faces) {
        const vec3 normal = cross(f.u, f.v);
        const double area = normal.length();
        if (!(area > tolerance * tolerance)) return nullptr;
        plane p{normal / area, 0};
        p.d = dot(p.n, f.corner);
        double below = 0, above = 0;
        for (const point3& c : corners) {
            const double s = dot(p.n, c) - p.d;
            below = std::fmin(below, s);
            above = std::fmax(above, s);
        }
        if (below < -tolerance && above > tolerance) return nullptr; // corners on both sides
        if (above > tolerance) {
            p.n = -p.n;
            p.d = -p.d;
        }
        result->planes_.push_back(p);
    }
    // Closed: every edge of every face is an edge of exactly one other face (either way round).
    auto same = [&](const point3& a, const point3& b) { return (a - b).length() <= tolerance; };
    for (size_t i = 0; i < faces.size(); ++i) {
        for (int e = 0; e < 4; ++e) {
            const point3& a = corners[4 * i + size_t(e)];
            const point3& b = corners[4 * i + size_t((e + 1) % 4)];
            int shared = 0;
            for (size_t j = 0; j < faces.size(); ++j) {
                if (j == i) continue;
                for (int k = 0; k < 4; ++k) {
                    const point3& c = corners[4 * j + size_t(k)];
                    const point3& d = corners[4 * j + size_t((k + 1) % 4)];
                    shared += (same(a, c) && same(b, d)) || (same(a, d) && same(b, c));
                }
            }
            if (shared != 1) return nullptr;
        }
    }
    result->density_ = medium.density();
    result->phase_owner_ = medium.phase_function();
    result->phase_function_ = std::shared_ptr<material>(std::shared_ptr<material>(), result->phase_owner_.get());
    result->box_ = medium.bounding_box();
    return result;
}

inline bool convex_medium::hit(const ray& r, interval ray_t, hit_record& rec) const {
    const double ray_length = r.direction().length();
    if (!(ray_length > 0) || !(density_ > 0) || !(ray_t.min < ray_t.max)) return false;
    // The inside part of the ray's line: after every plane it enters by, before every plane it
    // leaves by.
    double enter = -std::numeric_limits<double>::infinity(), leave = std::numeric_limits<double>::infinity();
    for (const plane& p : planes_) {
        const double along = dot(p.n, r.direction()), gap = p.d - dot(p.n, r.origin());
        if (along == 0) {
            if (gap < 0) return false; // parallel to the plane, outside it
            continue;
        }
        const double t = gap / along;
        if (along < 0)
            enter = std::fmax(enter, t);
        else
            leave = std::fmin(leave, t);
    }
    return constant_medium::scatter_in_chord(r, ray_length, enter, leave, ray_t, density_, phase_function_, rec);
}

} // namespace rt
