#pragma once
// hittable_list: a list of hittables that is itself a hittable (the books' world container).
// Also brings in transform.h (translate, rotate_y), as the book's hittable.h does (see the end).

#include "core/rng.h"
#include "hittable.h"

#include <cstddef>
#include <memory>
#include <vector>

namespace rt {

class hittable_list : public hittable {
  public:
    std::vector<std::shared_ptr<hittable>> objects;

    hittable_list() {}
    hittable_list(std::shared_ptr<hittable> object) { add(object); }

    void clear() { objects.clear(); }

    void add(std::shared_ptr<hittable> object) { objects.push_back(object); }

    using hittable::hit; // the older books' hit(r, t_min, t_max, rec) too
    bool hit(const ray& r, interval ray_t, hit_record& rec) const override {
        hit_record temp_rec;
        bool hit_anything = false;
        auto closest_so_far = ray_t.max;

        for (const auto& object : objects) {
            if (object->hit(r, interval(ray_t.min, closest_so_far), temp_rec)) {
                hit_anything = true;
                closest_so_far = temp_rec.t;
                rec = temp_rec;
            }
        }

        return hit_anything;
    }

    // The box around every object's box. Computed when asked rather than kept up to date in
    // add(), so that it stays right when code edits `objects` directly.
    aabb bounding_box() const override {
        aabb box;
        for (const auto& object : objects)
            if (object) box = aabb(box, object->bounding_box());
        return box;
    }

    // Book 3: a light made of several shapes. random() picks a member uniformly and draws towards
    // it, so the density of a direction is the average of the members' densities.
    double pdf_value(const point3& origin, const vec3& direction) const override {
        if (objects.empty()) return 0.0;
        double weight = 1.0 / static_cast<double>(objects.size());
        double sum = 0.0;
        for (const auto& object : objects) sum += weight * object->pdf_value(origin, direction);
        return sum;
    }

    vec3 random(const point3& origin) const override {
        if (objects.empty()) return hittable::random(origin); // nothing to aim at: the default direction
        int last = static_cast<int>(objects.size()) - 1;
        return objects[static_cast<size_t>(random_int(0, last))]->random(origin);
    }
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::hittable_list;
#endif

// Book 2 defines translate and rotate_y beside hittable, so a book main that includes
// hittable_list.h expects them. transform.h needs only hittable.h, so including it here, last,
// closes no cycle.
#include "transform.h"
