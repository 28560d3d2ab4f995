#pragma once
// user_sphere: a sphere written the way a user writes one from the books (its own hit() in double
// precision, not the built-in sphere), so that the renderer treats it as user code. bench
// --user-shapes and the user-shape tests render it. It reports its true bounding box, none (the
// default of hittable: all of space, as a book-1 class has), or a box it is given.

#include <rtweekend/aabb.h>
#include <rtweekend/hittable.h>
#include <rtweekend/material.h>

#include <atomic>
#include <cmath>
#include <memory>

namespace app {

class user_sphere : public rt::hittable {
  public:
    enum class box_kind { exact, none, given };

    user_sphere(rt::point3 c, double r, std::shared_ptr<rt::material> m, box_kind box = box_kind::exact,
                rt::aabb given = rt::aabb())
        : c_(c), r_(r), m_(std::move(m)), box_(box), given_(given) {}

    bool hit(const rt::ray& r, rt::interval t, rt::hit_record& rec) const override {
        if (calls) ++*calls;
        rt::vec3 oc = c_ - r.origin();
        double a = r.direction().length_squared(), h = dot(r.direction(), oc);
        double disc = h * h - a * (oc.length_squared() - r_ * r_);
        if (disc < 0) return false;
        double sq = std::sqrt(disc), root = (h - sq) / a;
        if (!t.surrounds(root)) {
            root = (h + sq) / a;
            if (!t.surrounds(root)) return false;
        }
        rec.t = root;
        rec.p = r.at(root);
        rec.set_face_normal(r, (rec.p - c_) / r_);
        rec.mat = m_;
        return true;
    }

    rt::aabb bounding_box() const override {
        switch (box_) {
        case box_kind::exact: return rt::aabb(c_ - rt::vec3(r_, r_, r_), c_ + rt::vec3(r_, r_, r_));
        case box_kind::none: return hittable::bounding_box();
        case box_kind::given: return given_;
        }
        return rt::aabb();
    }

    // When set, every call of hit() is counted here.
    std::atomic<long>* calls = nullptr;

  private:
    rt::point3 c_;
    double r_;
    std::shared_ptr<rt::material> m_;
    box_kind box_;
    rt::aabb given_;
};

} // namespace app
