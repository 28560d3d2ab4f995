// Every kind of every family answers every query the engine makes of it: the test walks each
// list (shapes, materials, lights, textures), builds an example of each kind, and checks each
// answer against a value worked out here by hand. A kind added to a list without an example here
// does not compile (example() has no overload for it), so a new kind arrives with its check.

#include <doctest/doctest.h>

#include "test_helpers.h"
#include "user_sphere.h"

#include <rtweekend/core/kind_list.h>
#include <rtweekend/core/material_kinds.h>
#include <rtweekend/rtweekend.h>
#include <rtweekend/scene/light_kinds.h>
#include <rtweekend/scene/scene_compiler.h>
#include <rtweekend/scene/shape_kinds.h>
#include <rtweekend/scene/texture_table.h>

#include <cmath>
#include <memory>
#include <string>

namespace test_kinds {

using namespace rt;

namespace {

// --- shapes -------------------------------------------------------------------------------------

// An example world holding one shape of the kind, of material m, hit by the ray from the origin
// along -z at t = 2 (the shape's near surface at z = -2), with its outward normal +z there.
std::shared_ptr<material> grey() { return std::make_shared<lambertian>(color(0.5, 0.5, 0.5)); }

hittable_list example(kind_tag<sphere_set>, std::shared_ptr<material> m) {
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, -3), 1, m));
    return world;
}
hittable_list example(kind_tag<triangle_set>, std::shared_ptr<material> m) {
    hittable_list world;
    world.add(std::make_shared<triangle>(point3(-1, -1, -2), point3(1, -1, -2), point3(0, 1, -2), m));
    return world;
}
hittable_list example(kind_tag<quad_set>, std::shared_ptr<material> m) {
    hittable_list world;
    world.add(std::make_shared<quad>(point3(-1, -1, -2), vec3(2, 0, 0), vec3(0, 2, 0), m));
    return world;
}
hittable_list example(kind_tag<user_shape_set>, std::shared_ptr<material> m) {
    hittable_list world;
    world.add(std::make_shared<app::user_sphere>(point3(0, 0, -3), 1, m));
    return world;
}
hittable_list example(kind_tag<moving_sphere_set>, std::shared_ptr<material> m) {
    // From (-1, 0, -3) at time 0 to (1, 0, -3) at time 1: at time 0.5 the still sphere above.
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(-1, 0, -3), point3(1, 0, -3), 1, m));
    return world;
}
hittable_list example(kind_tag<instance_set>, std::shared_ptr<material> m) {
    // A unit sphere stretched along x is an ellipsoid: an instance of the sphere, whose near
    // point on the axis is still at z = -2.
    hittable_list world;
    auto s = std::make_shared<sphere>(point3(0, 0, 0), 1, m);
    world.add(std::make_shared<translate>(std::make_shared<scale>(s, vec3(2, 1, 1)), vec3(0, 0, -3)));
    return world;
}

template <class K>
void check_shape_kind() {
    CAPTURE(std::string(K::name));
    const hittable_list world = example(kind_tag<K>{}, grey());
    const compiled_scene scene = compile_scene(world, point3(0, 0, 0));
    const K& set = scene.template set<K>();
    REQUIRE(set.size() == 1);
    CHECK(set.bytes() > 0);
    // The leaf kernel and the completion, through the scene's walk.
    ray3f r{{0, 0, 0}, {0, 0, -1}};
    r.time = 0.5f;
    surface_hit hit;
    REQUIRE(scene.intersect(r, hit));
    CHECK(hit.kind == shape_id<K>);
    CHECK(hit.t == doctest::Approx(2).epsilon(1e-5));
    CHECK(hit.p.z == doctest::Approx(-2).epsilon(1e-5));
    CHECK(hit.normal.z == doctest::Approx(1).epsilon(1e-5));
    CHECK(hit.front_face);
    CHECK(scene.occluded(r));
    r.dir = {0, 1, 0};
    CHECK_FALSE(scene.occluded(r));
    // The box the BVH holds holds the hit.
    CHECK(scene.bounds.lo.z <= hit.p.z);
    CHECK(scene.bounds.hi.z >= hit.p.z);
    // Texture coordinates: finite, in [0, 1] for the books' shapes.
    double u = -1, v = -1;
    scene.surface_coordinates(hit, u, v);
    CHECK(std::isfinite(u));
    CHECK(std::isfinite(v));
    // Culling: marking every shape culled keeps the front face the ray meets, and a ray from behind
    // the surface (inside the sphere, or past the flat shapes) no longer finds its back face, but
    // for a user's shape, whose hit() decides alone.
    compiled_scene culled = scene;
    culled.set_back_face_culling([](uint32_t) { return true; });
    surface_hit front, back;
    ray3f forward{{0, 0, 0}, {0, 0, -1}}, from_behind{{0, 0, -2.5f}, {0, 0, 1}};
    forward.time = from_behind.time = 0.5f;
    CHECK(culled.intersect_culling_back_faces(forward, front));
    CHECK(scene.intersect(from_behind, back));
    CHECK(culled.intersect_culling_back_faces(from_behind, back) == std::is_same_v<K, user_shape_set>);
    // Light sampling: an emitting shape of a light-sampled kind is a light whose samples lie on it.
    if constexpr (K::light_sampled) {
        const hittable_list lit = example(kind_tag<K>{}, std::make_shared<diffuse_light>(color(4, 4, 4), true));
        const compiled_scene ls = compile_scene(lit, point3(0, 0, 0));
        REQUIRE(ls.lights.lights.size() == 1);
        const light& l = ls.lights.lights[0];
        CHECK(l.shape == shape_id<K>);
        CHECK(ls.lights.light_at(shape_id<K>, l.shape_index) == 0);
        CHECK(l.area() > 0);
        pcg32 rng(3);
        for (int i = 0; i < 64; ++i) {
            light_choice c;
            if (!ls.lights.sample({0, 0, 0}, rng, c)) continue;
            // The sampled point is on the shape: a ray towards it hits the shape there.
            surface_hit at;
            REQUIRE(ls.intersect(ray3f{{0, 0, 0}, c.wi}, at));
            CHECK(length(at.p - c.y) < 1e-3f);
        }
    }
}

// --- materials ----------------------------------------------------------------------------------

compiled_material example(kind_tag<lambertian_bsdf>) { return compiled_material::of(lambertian_bsdf{{0.8f, 0.5f, 0.2f}}); }
compiled_material example(kind_tag<metal_bsdf>) { return compiled_material::of(metal_bsdf{{0.9f, 0.8f, 0.7f}, 0.3f}); }
compiled_material example(kind_tag<dielectric_bsdf>) { return compiled_material::of(dielectric_bsdf{1.5f}); }
compiled_material example(kind_tag<fresnel_glass_bsdf>) {
    return compiled_material::of(fresnel_glass_bsdf{1.5f, {0.1f, 0.2f, 0.3f}});
}
compiled_material example(kind_tag<conductor_bsdf>) {
    return compiled_material::of(conductor_bsdf{{1, 1, 1}, {0.18f, 0.42f, 1.37f}, {3.42f, 2.35f, 1.77f}});
}
compiled_material example(kind_tag<emitter_bsdf>) { return compiled_material::of(emitter_bsdf{{4, 5, 6}, false}); }
compiled_material example(kind_tag<isotropic_phase>) { return compiled_material::of(isotropic_phase{{0.5f, 0.6f, 0.7f}}); }
compiled_material example(kind_tag<plastic_bsdf>) {
    return compiled_material::of(plastic_bsdf{{0.5f, 0.3f, 0.2f}, 1.5f, float(fresnel_average(1.5))});
}
compiled_material example(kind_tag<blinn_phong_bsdf>) {
    return compiled_material::of(blinn_phong_bsdf{{0.4f, 0.4f, 0.4f}, {0.5f, 0.5f, 0.5f}, 30});
}
compiled_material example(kind_tag<course_brdf_bsdf>) {
    course_brdf_bsdf b;
    b.model = course_brdf_bsdf::model_t::torrance_sparrow;
    b.kd = {0.3f, 0.3f, 0.3f};
    b.ks = {0.6f, 0.5f, 0.4f};
    b.exponent = 40;
    b.eta = 0.2f;
    b.k = 3;
    return compiled_material::of(b);
}
compiled_material example(kind_tag<user_bsdf>) { return compiled_material::of(user_bsdf{}); }
compiled_material example(kind_tag<rough_conductor_bsdf>) {
    rough_conductor_bsdf b;
    b.distribution = {0.3f, 0.1f};
    b.f0 = {0.9f, 0.7f, 0.4f};
    static const rough_conductor_data data{false, {1, 1, 1}, {0, 0, 0}, {1, 1, 1}, ggx_anisotropic_albedo(b.distribution)};
    b.data = &data; // outlives every record made here
    return compiled_material::of(b);
}
compiled_material example(kind_tag<rough_dielectric_bsdf>) {
    rough_dielectric_bsdf b;
    b.refraction_index = 1.5f;
    b.distribution = {0.2f, 0.2f};
    return compiled_material::of(b);
}
compiled_material example(kind_tag<metal_rough_bsdf>) {
    metal_rough_bsdf b;
    b.base_colour = {0.6f, 0.3f, 0.2f};
    b.metallic = 0.5f;
    return compiled_material::of(b);
}

template <class K>
void check_material_kind() {
    CAPTURE(std::string(K::name));
    const compiled_material m = example(kind_tag<K>{});
    CHECK(m.is<K>());
    const material_properties& p = m.properties();
    const vec3f n{0, 0, 1};
    const shading_point sp{n, true};
    const vec3f wo = normalize(vec3f{0.3f, -0.2f, 0.9f});
    pcg32 rng(11);
    int delta = 0, density = 0, absorbed = 0;
    for (int i = 0; i < 2000; ++i) {
        material_sample s;
        if (!m.sample(wo, sp, rng, s)) {
            ++absorbed;
            continue;
        }
        REQUIRE(is_finite(s.wi));
        CHECK(std::fabs(length(s.wi) - 1) < 1e-4f);
        if (s.is_delta()) {
            ++delta;
            // A delta lobe has no density: a kind with no other lobe says 0 for its direction.
            if (!p.has_density) CHECK(m.pdf(wo, s.wi, sp) == 0);
            continue;
        }
        ++density;
        // A lobe with a density: sample's pdf and value are pdf() and eval() / pdf().
        const float pdf = m.pdf(wo, s.wi, sp);
        REQUIRE(pdf > 0);
        CHECK(std::fabs(s.pdf - pdf) <= 1e-4f * pdf);
        const vec3f f = m.eval(wo, s.wi, sp);
        for (int c = 0; c < 3; ++c) CHECK(std::fabs(s.value[c] - f[c] / pdf) <= 1e-3f * (1 + s.value[c]));
    }
    // What it draws is what its properties say it has.
    CHECK((delta > 0) == p.has_delta_lobe);
    CHECK((density > 0) == p.has_density);
    if (!p.scatters || p.user) CHECK(absorbed == 2000); // an emitter, a user's: the integrator's business
    // Emission: what emits() says, from the front face (and the back when two-sided).
    const vec3f le = m.emitted(wo, sp);
    CHECK(p.emits == (le.x > 0 || le.y > 0 || le.z > 0));
    CHECK((le.x == m.emission().x && le.y == m.emission().y && le.z == m.emission().z));
    const vec3f back = m.emitted(wo, shading_point{n, false});
    if (!p.two_sided) CHECK((back.x == 0 && back.y == 0 && back.z == 0));
    // Beer's law: all is left after no distance; less after some only when it absorbs inside.
    const vec3f t0 = m.transmittance(0), t1 = m.transmittance(1);
    CHECK((t0.x == 1 && t0.y == 1 && t0.z == 1));
    CHECK((t1.z < 1) == p.absorbs_inside);
    // The weights a course base and a light path ask.
    CHECK(m.properties().lambertian_only == std::is_same_v<K, lambertian_bsdf>);
    material_sample refraction;
    refraction.wi = normalize(vec3f{0.2f, 0.1f, -1.0f});
    refraction.sampled = delta_transmission;
    const float ratio = m.reversal_ratio(n, wo, true, refraction);
    CHECK(std::isfinite(ratio));
    CHECK(ratio >= 0);
    // A texture's colour replaces the kind's own where the kind takes one.
    const compiled_material coloured = m.with_colour({0.25f, 0.25f, 0.25f});
    if constexpr (K::takes_texture) {
        const vec3f e = p.emits ? coloured.emission() : coloured.eval(wo, n, sp);
        const vec3f e0 = p.emits ? m.emission() : m.eval(wo, n, sp);
        CHECK(e.x != e0.x);
    }
}

// --- lights -------------------------------------------------------------------------------------

light example(kind_tag<sphere_emitter>) { return {sphere_emitter{{0, 0, -3}, 1}, {1, 1, 1}}; }
light example(kind_tag<quad_emitter>) { return {quad_emitter{{-1, -1, -3}, {2, 0, 0}, {0, 2, 0}}, {1, 1, 1}}; }
light example(kind_tag<triangle_emitter>) { return {triangle_emitter{{-1, -1, -3}, {1, -1, -3}, {0, 1, -3}}, {1, 1, 1}}; }
light example(kind_tag<point_emitter>) { return {point_emitter{{0, 0, -3}}, {1, 1, 1}}; }
light example(kind_tag<hidden_square_emitter>) {
    light l{hidden_square_emitter{{0, 0, -3}, {2, 0, 0}, {0, 2, 0}, {0, 0, 1}, 4}, {1, 1, 1}};
    l.two_sided = true;
    return l;
}
light example(kind_tag<directional_emitter>) { return {directional_emitter{normalize(vec3f{1, 2, 3}), {0, 0, -3}, 2}, {1, 1, 1}}; }

// Its area in closed form.
float area_of(kind_tag<sphere_emitter>) { return 4 * pi_f; }
float area_of(kind_tag<quad_emitter>) { return 4; }
float area_of(kind_tag<triangle_emitter>) { return 2; }
float area_of(kind_tag<point_emitter>) { return 0; }
float area_of(kind_tag<directional_emitter>) { return 0; }
float area_of(kind_tag<hidden_square_emitter>) { return 0; } // a delta light: sampled, never met

template <class K>
void check_light_kind() {
    CAPTURE(typeid(K).name());
    const light l = example(kind_tag<K>{});
    const K& e = std::get<K>(l.emitter);
    CHECK(l.is_delta() == K::is_delta);
    CHECK(l.area() == doctest::Approx(area_of(kind_tag<K>{})).epsilon(1e-6));
    CHECK(e.area_in_double() == doctest::Approx(area_of(kind_tag<K>{})).epsilon(1e-6));
    CHECK(l.power() > 0);
    const vec3f p{0.1f, 0.2f, 0};
    pcg32 rng(5);
    for (int i = 0; i < 64; ++i) {
        light_sample s;
        REQUIRE(e.sample(p, rng.next_float(), rng.next_float(), s));
        CHECK(s.pdf > 0);
        CHECK(std::fabs(length(s.wi) - 1) < 1e-5f);
        CHECK(length(p + s.distance * s.wi - s.y) < 1e-4f);
        vec3f y, ny;
        if constexpr (K::is_delta) {
            CHECK_FALSE(e.meet(p, s.wi, y, ny)); // no direction finds a point
            CHECK(e.pdf(p, s.y, s.n) == 0);
            continue;
        }
        // The line towards the sample meets the light at the sample, where pdf() is sample()'s.
        REQUIRE(e.meet(p, s.wi, y, ny));
        CHECK(length(y - s.y) < 1e-4f);
        CHECK(e.pdf(p, y, ny) == doctest::Approx(s.pdf).epsilon(1e-4));
    }
    // A light path leaves it with a finite throughput.
    ray3f r;
    vec3f throughput;
    e.start_path(l.emission, l.two_sided, 1.0f, K::is_delta ? 0.0f : 1.0f / l.area(), box3f{}, rng, r, throughput);
    CHECK(is_finite(r.origin));
    CHECK(std::fabs(length(r.dir) - 1) < 1e-5f);
    CHECK(is_finite(throughput));
    CHECK(throughput.x > 0);
}

// --- textures -----------------------------------------------------------------------------------

struct texture_example {
    std::shared_ptr<texture> tex;
    vec3f at_origin; // its colour at (u, v) = (0.25, 0.75), p = (0.1, 0.2, 0.3), by hand
};

texture_example example(kind_tag<constant_colour>) {
    return {std::make_shared<solid_color>(color(0.1, 0.2, 0.3)), {0.1f, 0.2f, 0.3f}};
}
texture_example example(kind_tag<checker_pattern>) {
    // Cells of 0.5: floor(0.2) + floor(0.4) + floor(0.6) = 0 is even.
    return {std::make_shared<checker_texture>(0.5, color(1, 0, 0), color(0, 0, 1)), {1, 0, 0}};
}
texture_example example(kind_tag<image_pixels>) {
    // The book's magenta where an image could not be read.
    return {std::make_shared<image_texture>("no such image here.png"), {1, 0, 1}};
}
texture_example example(kind_tag<marble_noise>) {
    auto n = std::make_shared<noise_texture>(4.0);
    return {n, vec3f(n->value(0.25, 0.75, point3(0.1, 0.2, 0.3)))};
}
texture_example example(kind_tag<user_texture>) {
    struct gradient : texture {
        color value(double u, double v, const point3&) const override { return color(u, v, 0); }
    };
    return {std::make_shared<gradient>(), {0.25f, 0.75f, 0}};
}

template <class K>
void check_texture_kind() {
    CAPTURE(std::string(K::name));
    texture_example e = example(kind_tag<K>{});
    texture_table table;
    uint32_t i = 0;
    try {
        i = table.add(*e.tex);
    } catch (const scene_error&) {
        // An image_texture that could not be read is refused by the table (the scene compiler
        // names the file); its kind is still checked below on an image in memory.
        REQUIRE(std::is_same_v<K, image_pixels>);
        image_pixels pixels{std::make_shared<const std::vector<float>>(std::vector<float>{1, 0, 1}), 1, 1, true, image_sampling{}};
        table.entries.push_back(pixels);
        i = 0;
    }
    CHECK(std::holds_alternative<K>(table.entries[i]));
    const vec3f c = table.eval(i, 0.25f, 0.75f, vec3(0.1, 0.2, 0.3));
    CHECK(c.x == doctest::Approx(e.at_origin.x).epsilon(1e-6));
    CHECK(c.y == doctest::Approx(e.at_origin.y).epsilon(1e-6));
    CHECK(c.z == doctest::Approx(e.at_origin.z).epsilon(1e-6));
    const float a = table.average(i);
    CHECK(std::isfinite(a));
    CHECK(a >= 0);
    CHECK(table.calls_user_code() == K::calls_user_code);
}

} // namespace

TEST_CASE("kinds: every shape kind compiles, is hit, completes, gives coordinates and lights") {
    for_each_kind<shape_kinds>([](auto k) { check_shape_kind<typename decltype(k)::type>(); });
}

TEST_CASE("kinds: every material kind samples what it evaluates, and says what it has") {
    for_each_kind<material_kinds>([](auto k) { check_material_kind<typename decltype(k)::type>(); });
}

TEST_CASE("kinds: every light kind samples points it meets, with the density it reports") {
    for_each_kind<light_kinds>([](auto k) { check_light_kind<typename decltype(k)::type>(); });
}

TEST_CASE("kinds: every texture kind gives its colour, its mean, and whether it calls user code") {
    for_each_kind<texture_kinds>([](auto k) { check_texture_kind<typename decltype(k)::type>(); });
}

TEST_CASE("kinds: the lists number their kinds, and the dispatch reaches each") {
    // A kind's number is its place in the list, and visit_kind reaches the kind of that number.
    for_each_kind<shape_kinds>([](auto k) {
        using K = typename decltype(k)::type;
        const std::string name = with_shape_kind(shape_id<K>, [](auto j) { return std::string(decltype(j)::type::name); });
        CHECK(name == K::name);
    });
    size_t count = 0;
    for_each_kind<material_kinds>([&](auto k) {
        using K = typename decltype(k)::type;
        CHECK(kind_index<K, material_kinds> == count);
        CHECK(example(k).kind() == count);
        ++count;
    });
    CHECK(count == material_kinds::size);
    // The one recogniser: exact classes only.
    struct my_lambertian : lambertian {
        using lambertian::lambertian;
    };
    CHECK(exact_kind<book_materials>(lambertian(color(1, 1, 1))) == kind_index<lambertian, book_materials>);
    CHECK(exact_kind<book_materials>(my_lambertian(color(1, 1, 1))) == book_materials::size);
    CHECK(compile_material(my_lambertian(color(1, 1, 1))).is_user());
}

} // namespace test_kinds
