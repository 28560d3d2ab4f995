// aabb (rtweekend/aabb.h), book 2's bounding box, the interval operations it needs, and the
// bounding_box() of every built-in hittable. Expected boxes are written out by hand.

#include <rtweekend/aabb.h>
#include <rtweekend/hittable_list.h>
#include <rtweekend/material.h>
#include <rtweekend/mesh.h>
#include <rtweekend/sphere.h>
#include <rtweekend/triangle.h>

#include <doctest/doctest.h>

#include <limits>
#include <memory>

namespace test_aabb {

using namespace rt;

namespace {

const double inf_d = std::numeric_limits<double>::infinity();

void check_interval(const interval& i, double lo, double hi) {
    CHECK(i.min == doctest::Approx(lo).epsilon(1e-12));
    CHECK(i.max == doctest::Approx(hi).epsilon(1e-12));
}

void check_box(const aabb& b, const point3& lo, const point3& hi) {
    check_interval(b.x, lo.x(), hi.x());
    check_interval(b.y, lo.y(), hi.y());
    check_interval(b.z, lo.z(), hi.z());
}

// A shape that is not built in and keeps the default bounding_box().
class book1_shape : public hittable {
  public:
    bool hit(const ray&, interval, hit_record&) const override { return false; }
};

} // namespace

TEST_CASE("interval: the union of two intervals, and shifting by a displacement") {
    check_interval(interval(interval(1, 3), interval(2, 5)), 1, 5);
    check_interval(interval(interval(-4, -2), interval(6, 7)), -4, 7); // disjoint: the gap is inside
    check_interval(interval(interval::empty, interval(2, 3)), 2, 3);   // empty adds nothing
    CHECK(interval(interval::empty, interval::empty).size() < 0);
    check_interval(interval(1, 2) + 10, 11, 12);
    check_interval(-1.5 + interval(1, 2), -0.5, 0.5);
}

TEST_CASE("aabb: corners in any order, padding of flat axes, union of boxes") {
    check_box(aabb(point3(1, 5, -2), point3(-3, 2, 4)), point3(-3, 2, -2), point3(1, 5, 4));
    check_box(aabb(interval(0, 1), interval(2, 3), interval(4, 6)), point3(0, 2, 4), point3(1, 3, 6));
    // A flat box (z from 0 to 0) is padded to 0.0001 about its middle, as in book 2; the other axes
    // keep their extent. A point becomes a cube of side 0.0001.
    check_box(aabb(point3(0, 0, 0), point3(1, 2, 0)), point3(0, 0, -0.00005), point3(1, 2, 0.00005));
    check_box(aabb(point3(1, 1, 1), point3(1, 1, 1)), point3(0.99995, 0.99995, 0.99995), point3(1.00005, 1.00005, 1.00005));
    // The union of two boxes, and of a box with the empty one.
    aabb a(point3(0, 0, 0), point3(1, 1, 1)), b(point3(2, -1, 0.5), point3(3, 0.5, 4));
    check_box(aabb(a, b), point3(0, -1, 0), point3(3, 1, 4));
    check_box(aabb(aabb::empty, a), point3(0, 0, 0), point3(1, 1, 1));
    CHECK(aabb().x.size() < 0); // the default box is empty
    CHECK(aabb::universe.y.min == -inf_d);
    CHECK(aabb::universe.y.max == inf_d);
}

TEST_CASE("aabb: axis_interval, longest_axis and translation") {
    aabb box(point3(0, 0, 0), point3(2, 5, 3));
    CHECK(&box.axis_interval(0) == &box.x);
    CHECK(&box.axis_interval(1) == &box.y);
    CHECK(&box.axis_interval(2) == &box.z);
    CHECK(box.longest_axis() == 1);
    CHECK(aabb(point3(0, 0, 0), point3(7, 5, 3)).longest_axis() == 0);
    CHECK(aabb(point3(0, 0, 0), point3(1, 5, 9)).longest_axis() == 2);
    check_box(box + vec3(1, -2, 0.5), point3(1, -2, 0.5), point3(3, 3, 3.5));
    check_box(vec3(1, -2, 0.5) + box, point3(1, -2, 0.5), point3(3, 3, 3.5));
}

TEST_CASE("aabb::hit: the slab test against hand-placed rays") {
    const aabb unit(point3(0, 0, 0), point3(1, 1, 1));
    const interval forward(0, inf_d);
    // Along +x through the middle: enters at t = 5, leaves at t = 6.
    const ray through(point3(-5, 0.5, 0.5), vec3(1, 0, 0));
    CHECK(unit.hit(through, forward));
    CHECK_FALSE(unit.hit(through, interval(0, 4.9)));   // stops before the box
    CHECK_FALSE(unit.hit(through, interval(6.1, 100))); // starts after it
    CHECK(unit.hit(through, interval(5.5, 5.6)));       // entirely inside it
    // The same line backwards: the box is behind the origin.
    CHECK_FALSE(unit.hit(ray(point3(-5, 0.5, 0.5), vec3(-1, 0, 0)), forward));
    // Beside the box: y = 1.5 never enters the slab 0 <= y <= 1.
    CHECK_FALSE(unit.hit(ray(point3(-5, 1.5, 0.5), vec3(1, 0, 0)), forward));
    // A diagonal ray from inside.
    CHECK(unit.hit(ray(point3(0.5, 0.5, 0.5), vec3(1, 2, 3)), forward));
    // Diagonally past a corner: the ray (t, t, 2.5 - t) is inside x and y for t in [0, 1] but
    // inside z only for t in [1.5, 2.5].
    CHECK_FALSE(unit.hit(ray(point3(0, 0, 2.5), vec3(1, 1, -1)), forward));
    // The empty box is never hit; everything is inside the universe.
    CHECK_FALSE(aabb::empty.hit(through, forward));
    CHECK(aabb::universe.hit(through, forward));
}

TEST_CASE("bounding_box of the built-in hittables, the list, and a book-1 shape") {
    auto m = std::make_shared<lambertian>(color(0.5, 0.5, 0.5));
    sphere s(point3(1, 2, 3), 0.5, m);
    check_box(s.bounding_box(), point3(0.5, 1.5, 2.5), point3(1.5, 2.5, 3.5));
    triangle t(point3(0, 0, 0), point3(2, 1, 0), point3(1, 3, 4), m);
    check_box(t.bounding_box(), point3(0, 0, 0), point3(2, 3, 4));
    // Flat in z: padded there only.
    triangle flat(point3(0, 0, 1), point3(2, 0, 1), point3(0, 3, 1), m);
    check_box(flat.bounding_box(), point3(0, 0, 0.99995), point3(2, 3, 1.00005));
    // A mesh's box holds the vertices its faces use (vertex 3 is used by no face).
    triangle_mesh mesh({point3(0, 0, 0), point3(1, 0, 0), point3(0, 2, 1), point3(50, 50, 50)}, {{0, 1, 2}}, m);
    check_box(mesh.bounding_box(), point3(0, 0, 0), point3(1, 2, 1));

    hittable_list list;
    CHECK(list.bounding_box().x.size() < 0); // empty list: empty box
    list.add(std::make_shared<sphere>(point3(0, 0, 0), 1, m));
    list.add(std::make_shared<sphere>(point3(5, 0, 0), 2, m));
    check_box(list.bounding_box(), point3(-1, -2, -2), point3(7, 2, 2));
    // Editing objects directly is seen too (the box is not cached).
    list.objects.pop_back();
    check_box(list.bounding_box(), point3(-1, -1, -1), point3(1, 1, 1));
    // A shape written before book 2 has no box of its own: the default is all of space, and a
    // list holding one is unbounded too.
    CHECK(book1_shape().bounding_box().x.min == -inf_d);
    list.add(std::make_shared<book1_shape>());
    CHECK(list.bounding_box().z.max == inf_d);
}

} // namespace test_aabb
