#pragma once
// bvh_node: book 2's bounding volume hierarchy, a binary tree of hittables that is itself a
// hittable.
//
//   world = hittable_list(make_shared<bvh_node>(world));
//
// The renderer does not need it: it compiles every world into its own eight-wide BVH
// (scene/bvh.h) and looks through a bvh_node to the shapes below, as it does through a
// hittable_list, so wrapping a world in one changes nothing in the image or the speed. The tree
// here serves code that calls hit() itself (a book-style ray_color of one's own): each node splits
// its objects at the median of their bounding boxes' centres along the longest axis of the box
// around them, so a ray tests O(log n) boxes instead of every object.
//
// As in the book, a node over one object holds it on both sides; the renderer takes it once.
// The constructor with times (the book's older form, bvh_node(list, time0, time1)) ignores them:
// bounding boxes of moving shapes already cover their whole motion.

#include "aabb.h"
#include "hittable.h"
#include "hittable_list.h"
#include "interval.h"
#include "ray.h"
#include "core/scene_error.h"

#include <algorithm>
#include <cstddef>
#include <memory>
#include <vector>

namespace rt {

class bvh_node : public hittable {
  public:
    bvh_node(hittable_list list) : bvh_node(list.objects, 0, list.objects.size()) {}
    bvh_node(const hittable_list& list, double /*time0*/, double /*time1*/) : bvh_node(hittable_list(list)) {}
    // A tree over objects[start, end), which it reorders.
    bvh_node(std::vector<std::shared_ptr<hittable>>& objects, size_t start, size_t end);

    bool hit(const ray& r, interval ray_t, hit_record& rec) const override;
    aabb bounding_box() const override { return bbox_; }

    // The two subtrees (the same object twice for a node over one).
    const std::shared_ptr<hittable>& left() const { return left_; }
    const std::shared_ptr<hittable>& right() const { return right_; }

  private:
    std::shared_ptr<hittable> left_, right_;
    aabb bbox_;
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline bvh_node::bvh_node(std::vector<std::shared_ptr<hittable>>& objects, size_t start, size_t end) {
    if (!(start < end && end <= objects.size())) throw scene_error("bvh_node needs at least one object");
    for (size_t i = start; i < end; ++i) {
        if (!objects[i]) throw scene_error("bvh_node given a null object");
        bbox_ = aabb(bbox_, objects[i]->bounding_box());
    }
    const size_t count = end - start;
    if (count == 1) {
        left_ = right_ = objects[start];
        return;
    }
    if (count == 2) {
        left_ = objects[start];
        right_ = objects[start + 1];
        return;
    }
    // Split at the median centre along the longest axis of the box around the objects: each
    // half gets half the objects, so the tree is balanced whatever their sizes.
    const int axis = bbox_.longest_axis();
    auto centre = [axis](const std::shared_ptr<hittable>& h) {
        const interval slab = h->bounding_box().axis_interval(axis); // a copy: the box is a temporary
        return slab.min + slab.max; // twice the centre: the order is what counts
    };
    const size_t mid = start + count / 2;
    std::nth_element(objects.begin() + std::ptrdiff_t(start), objects.begin() + std::ptrdiff_t(mid),
                     objects.begin() + std::ptrdiff_t(end),
                     [&](const auto& a, const auto& b) { return centre(a) < centre(b); });
    left_ = std::make_shared<bvh_node>(objects, start, mid);
    right_ = std::make_shared<bvh_node>(objects, mid, end);
}

inline bool bvh_node::hit(const ray& r, interval ray_t, hit_record& rec) const {
    if (!bbox_.hit(r, ray_t)) return false;
    const bool hit_left = left_->hit(r, ray_t, rec);
    // The right side only needs to beat the left's hit.
    const bool hit_right = right_ != left_ && right_->hit(r, interval(ray_t.min, hit_left ? rec.t : ray_t.max), rec);
    return hit_left || hit_right;
}

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::bvh_node;
#endif
