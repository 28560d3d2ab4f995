#pragma once
// hittable_list: a list of hittables that is itself a hittable (the books' world container).

#include "hittable.h"

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
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::hittable_list;
#endif
