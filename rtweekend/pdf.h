#pragma once
// pdf: a probability density over directions that can also draw from itself (book 3), for
// importance sampling in a ray_color of one's own:
//
//   value(d)      the solid-angle density of direction d (d need not be a unit vector)
//   generate()    a direction drawn with that density (not necessarily a unit vector)
//
//   sphere_pdf                    uniform over all directions, 1 / (4 pi)
//   cosine_pdf(w)                 cos(theta) / pi about the unit direction w, 0 below it
//   hittable_pdf(objects, p)      towards a shape (or a list of them) seen from p, through the
//                                 shape's pdf_value() and random()
//   mixture_pdf(p0, p1)           the even mixture of two pdfs
//
// The draws come from random_double(), as everything the book's code draws does, so inside a
// render they come from the current sample's generator.
//
// hittable_pdf keeps a reference to the shape, as the book's does: the shape must outlive it.

#include "core/constants.h"
#include "hittable.h"
#include "onb.h"
#include "vec3.h"

#include <cmath>
#include <memory>

namespace rt {

class pdf {
  public:
    virtual ~pdf() = default;

    virtual double value(const vec3& direction) const = 0;
    virtual vec3 generate() const = 0;
};

class sphere_pdf : public pdf {
  public:
    sphere_pdf() {}

    double value(const vec3& /*direction*/) const override { return 1 / (4 * pi); }
    vec3 generate() const override { return random_unit_vector(); }
};

class cosine_pdf : public pdf {
  public:
    cosine_pdf(const vec3& w) : uvw_(w) {}

    double value(const vec3& direction) const override {
        double cosine_theta = dot(unit_vector(direction), uvw_.w());
        return std::fmax(0.0, cosine_theta / pi);
    }

    vec3 generate() const override { return uvw_.transform(random_cosine_direction()); }

  private:
    onb uvw_;
};

class hittable_pdf : public pdf {
  public:
    hittable_pdf(const hittable& objects, const point3& origin) : objects_(objects), origin_(origin) {}

    double value(const vec3& direction) const override { return objects_.pdf_value(origin_, direction); }
    vec3 generate() const override { return objects_.random(origin_); }

  private:
    const hittable& objects_;
    point3 origin_;
};

class mixture_pdf : public pdf {
  public:
    mixture_pdf(std::shared_ptr<pdf> p0, std::shared_ptr<pdf> p1) : p_{std::move(p0), std::move(p1)} {}

    // Half of each: generate() picks either with probability 1/2, so its density is the average.
    double value(const vec3& direction) const override {
        return 0.5 * p_[0]->value(direction) + 0.5 * p_[1]->value(direction);
    }

    vec3 generate() const override { return random_double() < 0.5 ? p_[0]->generate() : p_[1]->generate(); }

  private:
    std::shared_ptr<pdf> p_[2];
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::cosine_pdf;
using rt::hittable_pdf;
using rt::mixture_pdf;
using rt::pdf;
using rt::sphere_pdf;
#endif
