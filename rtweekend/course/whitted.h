#pragma once
// The classic recursive ray tracer (T. Whitted, "An Improved Illumination Model for Shaded
// Display", CACM 1980), as the CENG795 course defines it (docs/course.md): one ray per
// pixel, point and ambient lights, Lambert diffuse plus Blinn-Phong specular, shadow rays, and
// recursion through mirrors, conductors and dielectrics up to max_recursion_depth bounces.
//
//   whitted_scene s = load_xml_scene("scene.xml");           // io/xml_scene.h
//   whitted_render r = render_whitted(s, 0);                   // camera 0
//   write_whitted_image("out.png", r.img);                     // clamp to 0..255, no gamma
//
// It traces the same compiled scene (BVH, float SIMD tests) as the path tracer and asks the same
// material contract (bsdf.h) for what the surfaces do:
//   - a point light of intensity I at distance d, seen along l, adds (I / d^2) pi eval(wo, l):
//     the course writes the diffuse term as kd (I / d^2) cos, which is pi times the radiance a
//     Lambertian of albedo kd reflects (eval is kd cos / pi), so its intensities are pi times
//     radiometric ones;
//   - the course's ambient term (ka times the ambient light) and its Blinn-Phong specular term
//     (ks (n.h)^p I / d^2) describe point-light shading, not a BSDF: they come from the
//     whitted_material itself (whitted_terms below) and other materials have none;
//   - mirrors, conductors and glass are the contract's delta lobes, sampled one lobe at a time
//     (reflection, then transmission) and followed while bounces remain; other lobes (a fuzzy
//     metal's) light the point through eval only;
//   - inside absorbing glass the radiance of a ray is attenuated over the distance to the next
//     surface by the material's transmittance (Beer's law);
//   - a hit on glass from inside (a ray travelling in a dielectric reaches its surface: the back
//     face of a dielectric) has no local shading: no ambient, diffuse or specular term, only its
//     reflected and refracted rays. That is the course's rule (docs/course.md; see
//     shade_inside_dielectrics below for the evidence); the opposite rule is an option.
// The image holds radiance in the course's units (255 is white), unclamped; encode_whitted_8bit
// clamps each channel to [0, 255] and truncates, as the course's reference images do.
//
// How much is traced. The recursion of the course's pseudocode is an explicit stack here, one
// small frame per bounce on the heap instead of a call on the thread's stack: two facing mirrors
// at MaxRecursionDepth 10000 once overflowed the stack. The arithmetic is the recursion's, in its
// order (a surface's radiance is its shading plus each lobe's weight times what that lobe's ray
// returns, attenuated inside absorbing glass), so images are unchanged bit for bit. A glass
// surface spawns two rays, so a tree of depth d may hold 2^(d+1) - 1 of them (a glass sphere
// between two mirrors at depth 60 never finished); two bounds, both in render_settings::whitted, keep the
// work of a camera ray finite:
//   - a branch is not followed when its weight, the product of the lobe weights (and Beer
//     transmittances) from the camera, is below 2^-18 in every channel: radiance of up to 256
//     (a white pixel) that it carried would change the pixel by less than 1/1024 of an 8-bit
//     code;
//   - at most 2^14 rays follow one camera ray (the branches met first, depth first, reflection
//     before transmission); the full tree of depth 12 has 8191, and the course's scenes use
//     depths up to about 6.
// The scenes in tests/data (and showcase and bunny_glass at depths 10 and 20) render to the same
// bytes with the bounds as without them.
//
// Interruption (render_settings::stop): the scheduler polls the flag before each pixel (one
// camera ray and its tree), so a render stops within one pixel; the pixels not reached are black
// (radiance 0), and render_stats says how many there are (interrupted, pixels_without_samples).

#include "../core/engine_linkage.h"
#include "../core/material_kinds.h"
#include "../core/rng.h"
#include "../image/image.h"
#include "../render/render_settings.h"
#include "../render/scheduler.h"
#include "../scene/surface_hit.h"
#include "course_surface_map.h"
#include "whitted_scene.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace rt {

class compiled_scene;

// Settings (render_settings, render/render_settings.h): the integrator takes one sample through
// the centre of each pixel; it reads threads, quiet, stop, share and keep_sums, and its own:
//   whitted.cull_back_faces       skip back faces of opaque objects for primary and reflected rays
//   whitted.min_branch_weight, whitted.max_branch_rays
//                                 the bounds on the tree of rays behind one camera ray (above)
//   whitted.shade_inside_dielectrics
//                                 whether a hit on a dielectric from inside gets the course's local
//                                 shading (ambient, diffuse and specular terms) as a hit from outside
//                                 does. Off: the course's rule, under which all the light leaving such
//                                 a hit is what its reflected and refracted rays bring. On: every hit
//                                 is shaded (this renderer's rule before; a shadow ray from inside
//                                 starts inside the glass and is blocked by it, so in practice the
//                                 difference is the ambient term ka Ia). The evidence for the course's
//                                 rule is in docs/course.md: CENG795 tracers written against the
//                                 instructor's reference images skip the shading there
//                                 (akifuslu/ceng795, scene.cpp), and the course scene with a shaded
//                                 glass (scienceTree_glass.xml) was reported brighter than the
//                                 reference only inside the glass while such hits were shaded.

struct whitted_render {
    image img;          // radiance, 0..255 per channel is the displayable range; not clamped
    render_stats stats; // rays counts camera, reflected, refracted and shadow rays
    pixel_sums sums;    // with render_settings::keep_sums: the exact sums behind img
};

// The course's point-light shading terms of a material that are not part of its BSDF: ambient
// reflectance and Blinn-Phong specular colour and exponent (zero for anything but a
// whitted_material).
struct whitted_terms {
    vec3f ambient{0, 0, 0}, specular{0, 0, 0};
    float phong_exponent = 1;
    float roughness = 0; // tilts the mirror and glass rays (whitted_material::roughness)
    vec3f emission{0, 0, 0}; // what a light object emits (whitted_material::radiance)
    // A material with a BRDF (homework 6): its f cos theta_i replaces the diffuse and specular
    // terms under every light (whitted_material::brdf).
    bool has_brdf = false;
    course_brdf_bsdf brdf;
    // An object with texture maps (homework 4): its index in the renderer's textured objects (-1:
    // none). Its maps change a copy of the material, and the shading normal, at each hit.
    int32_t textured = -1;

    static whitted_terms of(const compiled_material& m);
};

// Compiles the scene once, then renders any of its cameras, each with its own settings.
class whitted_renderer {
  public:
    explicit whitted_renderer(const whitted_scene& scene);
    // The settings a render takes when none are given: one thread per processor, quiet.
    static render_settings defaults() {
        render_settings s;
        s.samples_per_pixel = 1;
        s.quiet = true;
        return s;
    }
    whitted_render render(size_t camera_index, const render_settings& settings = defaults()) const;
    const compiled_scene& compiled() const { return *compiled_; }

  private:
    // A delta lobe's ray, waiting to be traced.
    struct branch {
        ray3f ray;
        vec3f weight;            // the lobe's sample value
        compiled_material medium; // the glass the ray travels inside, when `absorbing`
        bool absorbing = false;
    };
    // One surface on the path from the camera: what the recursion kept in a call's locals.
    struct frame {
        vec3f L{0, 0, 0};      // its shading, plus each branch's contribution once it returns
        vec3f weight{1, 1, 1}; // the product of lobe weights and transmittances from the camera
        vec3f attenuation{1, 1, 1}; // Beer's law over the ray that reached it, when `attenuated`
        bool attenuated = false;
        branch branches[2];    // reflection, then transmission
        int count = 0, taken = 0;
        vec3f in_flight{0, 0, 0}; // the weight of the branch being traced
    };

    bool intersect(const ray3f& r, surface_hit& hit, const whitted_settings& w) const;
    // The radiance arriving along a camera ray; `background` is what it sees if it misses.
    vec3f trace(const ray3f& r, const vec3f& background, pcg32& rng, uint64_t& rays, const whitted_settings& w) const;
    // Fills `f` for a hit at the given depth: local shading, and the delta lobes to follow. A
    // normal or bump map changes the hit's shading normal.
    void open(surface_hit& hit, const ray3f& r, int depth, pcg32& rng, uint64_t& rays, frame& f,
              const whitted_settings& w) const;
    vec3f shade(const surface_hit& hit, const ray3f& r, const compiled_material& m, const whitted_terms& terms,
                pcg32& rng, uint64_t& rays, bool ambient = true) const;
    // The course's f(wo, wi) cos theta_i of a material: what shade() multiplies a light's E by.
    static vec3f course_f_cos(const compiled_material& m, const whitted_terms& terms, const vec3f& wo, const vec3f& wi,
                              const shading_point& sp);
    // The material at a hit (a user shape's own, a texture's colour looked up, a course texture
    // map's change) and its terms. A course replace_all map replaces the local shading by `replaced`.
    struct hit_material {
        std::optional<compiled_material> reported, looked_up;
        std::optional<whitted_terms> reported_terms, mapped_terms;
        std::optional<whitted_material> mapped; // the textured object's material, its maps applied
        const compiled_material* m = nullptr;
        const whitted_terms* terms = nullptr;
        bool replaced = false;
        vec3f replaced_shading{0, 0, 0};
    };
    // Fills `out`; a course normal or bump map changes hit.shading_normal.
    void material_at(surface_hit& hit, hit_material& out) const;
    // The course's path tracer (homework 6): the radiance arriving along a camera ray.
    vec3f trace_path(const ray3f& r, const vec3f& background, pcg32& rng, uint64_t& rays,
                     const view_camera::path_tracing_t& pt, const whitted_settings& w) const;
    ray3f spawn(const surface_hit& hit, const vec3f& side, const vec3f& dir) const;

    // What rendering needs of the scene besides its geometry, copied: the renderer does not
    // depend on the whitted_scene staying alive.
    std::vector<view_camera> cameras_;
    vec3f background_, ambient_light_;
    float shadow_ray_epsilon_ = 0;
    int max_recursion_depth_ = 0;
    std::shared_ptr<const compiled_scene> compiled_; // shared by the renderer's copies
    std::vector<whitted_terms> terms_; // by compiled material index
    // A light as shade() asks it (course_lights.h has the formulas).
    struct light_f {
        enum kind_t { point, directional, spot, area, mesh, sphere } kind = point;
        vec3f position;  // relative to the compiled scene's origin: point, spot, area (its centre)
        vec3f intensity; // I (point, spot) or radiance (directional, area)
        vec3f axis;      // unit: towards the light (directional), the cone's axis (spot), the normal (area)
        vec3f edge_u, edge_v; // area: the square's edges, each of length size
        float square_area = 0;
        spot_light cone;  // spot: the fall-off
        uint32_t object = 0; // mesh, sphere: index into mesh_lights_ or sphere_lights_
    };
    std::vector<light_f> lights_;
    // A LightMesh: its triangles relative to the scene's origin, the running sum of their areas
    // (to pick one by area), and the whole area.
    struct mesh_light_f {
        std::vector<vec3f> a, e1, e2;
        std::vector<double> cumulative_area;
        double area = 0;
    };
    std::vector<mesh_light_f> mesh_lights_;
    // A LightSphere: its object-space sphere and the map out (in double: light_sphere's).
    struct sphere_light_f {
        vec3 center, offset; // offset relative to the scene's origin
        double radius = 0, det = 1;
        mat3 linear, normal_map; // M and M^-T
    };
    std::vector<sphere_light_f> sphere_lights_;
    std::vector<environment_light> environments_; // course_lights.h
    std::vector<course_surface_map> textured_;     // whitted_terms::textured indexes it
    std::optional<texture_map> background_map_;    // replace_background: the film's background
    // What a ray that leaves the scene in direction d sees of the environment lights: their sum
    // (0 without any).
    vec3f sky(const vec3f& d) const {
        vec3f L{0, 0, 0};
        for (const environment_light& e : environments_) L += e.radiance(d);
        return L;
    }
};

// Renders camera `camera_index` of the scene.
RTWEEKEND_ENGINE_FUNCTION whitted_render render_whitted(const whitted_scene& scene, size_t camera_index,
                                                        const render_settings& settings = whitted_renderer::defaults());

// The course's 8-bit encoding: each channel clamped to [0, 255] and truncated (NaN gives 0).
RTWEEKEND_ENGINE_FUNCTION std::vector<unsigned char> encode_whitted_8bit(const image& img);

// Writes the image as .png or .ppm (P3) in that encoding, or .pfm or .exr with the raw radiance;
// atomically.
RTWEEKEND_ENGINE_FUNCTION void write_whitted_image(const std::string& path, const image& img);

// Writes camera `cam`'s image to `path`: as write_whitted_image, unless the camera has a <Tonemap>
// (homework 5). Then the 8-bit file (a .png, .ppm or .bmp path) holds the photographic tone
// mapping (image/tonemap.h) and an EXR of the same stem the linear radiance; a linear path (.exr or
// .pfm) holds the radiance and a PNG of the same stem the tone mapping, as the course's references
// come in pairs. Returns the second file's path ("" when there is none). Both atomically.
RTWEEKEND_ENGINE_FUNCTION std::string write_course_image(const std::string& path, const image& img,
                                                         const view_camera& cam);

// --- IMPLEMENTATION -----------------------------------------------------------------------------
// Left out of a program that links the engine (core/engine_linkage.h).
#if RTWEEKEND_ENGINE_BODIES

} // namespace rt

#include "../core/input_limits.h"
#include "../core/ray_offset.h"
#include "../core/sampling.h"
#include "../image/image_write.h"
#include "../scene/compiled_scene.h"
#include "../scene/scene_compiler.h"
#include "../scene/surface_coordinates.h"
#include "../scene/validate.h"
#include "../whitted_material.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

namespace rt {

RTWEEKEND_ENGINE_FUNCTION whitted_terms whitted_terms::of(const compiled_material& m) {
    if (m.is_user())
        throw scene_error("the Whitted integrator cannot shade a user-written material (it has only scatter()): "
                          "use whitted_material or a built-in material");
    whitted_terms t;
    if (auto* w = dynamic_cast<const whitted_material*>(m.source)) {
        t.ambient = vec3f(w->ambient);
        t.specular = vec3f(w->specular);
        t.phong_exponent = static_cast<float>(w->phong_exponent);
        t.roughness = static_cast<float>(w->roughness);
        t.emission = vec3f(w->radiance);
        if (w->brdf) {
            t.has_brdf = true;
            t.brdf = w->course_brdf();
            t.specular = {0, 0, 0};
        }
    }
    return t;
}

RTWEEKEND_ENGINE_FUNCTION whitted_renderer::whitted_renderer(const whitted_scene& scene)
    : cameras_(scene.cameras) {
    auto compiled = std::make_shared<compiled_scene>(
        compile_scene(scene.world, scene.cameras.empty() ? point3(0, 0, 0) : scene.cameras[0].position));
    if (!std::isfinite(scene.shadow_ray_epsilon) || scene.shadow_ray_epsilon < 0)
        throw scene_error("shadow ray epsilon must be finite and non-negative");
    if (scene.max_recursion_depth < 0) throw scene_error("max recursion depth must be non-negative");
    check_color(scene.background, "background colour");
    check_color(scene.ambient_light, "ambient light");
    background_ = vec3f(scene.background);
    ambient_light_ = vec3f(scene.ambient_light);
    shadow_ray_epsilon_ = float(scene.shadow_ray_epsilon);
    max_recursion_depth_ = scene.max_recursion_depth;
    // The course's specular term is point-light shading here (whitted_terms), not the path
    // tracer's glossy lobe: a course material is shaded through its Lambertian base alone.
    for (compiled_material& m : compiled->materials)
        if (auto* w = dynamic_cast<const whitted_material*>(m.source)) m = w->compiled(false);
    for (const compiled_material& m : compiled->materials) terms_.push_back(whitted_terms::of(m));
    for (const point_light& l : scene.lights) {
        if (!finite3(l.position)) throw scene_error("point light position must be finite");
        check_color(l.intensity, "point light intensity");
        light_f f;
        f.position = vec3f(l.position - compiled->origin);
        f.intensity = vec3f(l.intensity);
        lights_.push_back(f);
    }
    auto unit_direction = [](const vec3& d, const char* what) {
        if (!finite3(d) || !(d.length_squared() > 0)) throw scene_error(std::string(what) + " must be a non-zero finite vector");
        return unit_vector(d);
    };
    for (const directional_light& l : scene.directional_lights) {
        check_color(l.irradiance, "directional light radiance");
        light_f f;
        f.kind = light_f::directional;
        f.axis = vec3f(-unit_direction(l.direction, "directional light direction"));
        f.intensity = vec3f(l.irradiance);
        lights_.push_back(f);
    }
    for (const spot_light& l : scene.spot_lights) {
        if (!finite3(l.position)) throw scene_error("spot light position must be finite");
        check_color(l.intensity, "spot light intensity");
        if (!(l.falloff_degrees >= 0 && l.falloff_degrees <= l.coverage_degrees && l.coverage_degrees <= 360))
            throw scene_error("spot light angles must satisfy 0 <= falloff <= coverage <= 360 degrees");
        light_f f;
        f.kind = light_f::spot;
        f.position = vec3f(l.position - compiled->origin);
        f.axis = vec3f(unit_direction(l.direction, "spot light direction"));
        f.intensity = vec3f(l.intensity);
        f.cone = l;
        lights_.push_back(f);
    }
    for (const light_mesh& l : scene.light_meshes) {
        check_color(l.radiance, "light mesh radiance");
        mesh_light_f m;
        for (const auto& t : l.triangles) {
            const vec3 e1 = t[1] - t[0], e2 = t[2] - t[0];
            const double area = 0.5 * cross(e1, e2).length();
            if (!(area > 0) || !std::isfinite(area)) continue; // a degenerate triangle emits nothing
            m.a.push_back(vec3f(t[0] - compiled->origin));
            m.e1.push_back(vec3f(e1));
            m.e2.push_back(vec3f(e2));
            m.area += area;
            m.cumulative_area.push_back(m.area);
        }
        if (m.a.empty()) continue;
        light_f f;
        f.kind = light_f::mesh;
        f.intensity = vec3f(l.radiance);
        f.object = uint32_t(mesh_lights_.size());
        mesh_lights_.push_back(std::move(m));
        lights_.push_back(f);
    }
    for (const light_sphere& l : scene.light_spheres) {
        check_color(l.radiance, "light sphere radiance");
        sphere_light_f s;
        s.center = l.center;
        s.radius = l.radius;
        s.linear = l.linear;
        s.det = std::fabs(l.linear.determinant());
        s.normal_map = l.linear.inverse().transpose();
        s.offset = l.offset - compiled->origin;
        if (!(s.radius > 0) || !(s.det > 0) || !std::isfinite(s.det)) throw scene_error("light sphere must have a positive radius and an invertible map");
        light_f f;
        f.kind = light_f::sphere;
        f.intensity = vec3f(l.radiance);
        f.object = uint32_t(sphere_lights_.size());
        sphere_lights_.push_back(s);
        lights_.push_back(f);
    }
    for (const area_light& l : scene.area_lights) {
        if (!finite3(l.position)) throw scene_error("area light position must be finite");
        check_color(l.radiance, "area light radiance");
        if (!(l.size > 0) || !std::isfinite(l.size)) throw scene_error("area light size must be positive and finite");
        const vec3 n = unit_direction(l.normal, "area light normal");
        vec3 u, v;
        course_frame(n, u, v);
        light_f f;
        f.kind = light_f::area;
        f.position = vec3f(l.position - compiled->origin);
        f.axis = vec3f(n);
        f.edge_u = vec3f(l.size * u);
        f.edge_v = vec3f(l.size * v);
        f.square_area = float(l.size * l.size);
        f.intensity = vec3f(l.radiance);
        lights_.push_back(f);
    }
    for (const environment_light& e : scene.environment_lights) {
        if (!e.map || e.map->width() <= 0 || e.map->height() <= 0)
            throw scene_error("environment light has no image");
        environments_.push_back(e);
    }
    for (const textured_object& o : scene.textured_objects) {
        const auto index = int32_t(textured_.size());
        textured_.emplace_back(o); // checks the maps and the placement
        for (size_t k = 0; k < compiled->materials.size(); ++k)
            if (compiled->materials[k].source == o.surface.get()) terms_[k].textured = index;
    }
    if (scene.background_texture) {
        check_texture_map(*scene.background_texture);
        background_map_ = scene.background_texture;
    }
    // Back faces the culled walk skips (whitted_settings::cull_back_faces asks for it per render).
    compiled->set_back_face_culling([&](uint32_t m) { return !compiled->materials[m].transmits(); });
    compiled_ = std::move(compiled);
}

// A secondary ray from the hit point, offset by the shadow-ray epsilon (and the float error of
// the hit point) to the side `side` of the surface.
RTWEEKEND_ENGINE_FUNCTION ray3f whitted_renderer::spawn(const surface_hit& hit, const vec3f& side,
                                                        const vec3f& dir) const {
    ray3f r;
    r.origin = offset_ray_origin(hit.p, side) + (hit.offset + shadow_ray_epsilon_) * side;
    r.dir = dir;
    r.tmin = 0;
    r.tmax = std::numeric_limits<float>::infinity();
    r.time = hit.time; // the time of the ray that found the hit
    return r;
}

// Ambient, plus what every light the point sees adds: its irradiance E (course_lights.h) times
// the material's eval towards the light and the course's Blinn-Phong specular term. An area light
// is sampled at one point per call (two random numbers each; the other lights draw none).
RTWEEKEND_ENGINE_FUNCTION vec3f whitted_renderer::course_f_cos(const compiled_material& m, const whitted_terms& terms,
                                                               const vec3f& wo, const vec3f& wi, const shading_point& sp) {
    if (terms.has_brdf) return terms.brdf.course_value(wo, wi, sp.n);
    const vec3f diffuse = pi_f * m.eval(wo, wi, sp);
    if (detail::is_black(terms.specular)) return diffuse; // no power to take (ks is checked non-negative)
    const vec3f h = normalize(wi + wo);
    const float specular = std::pow(fmax_inline(0.0f, dot(sp.n, h)), terms.phong_exponent);
    return diffuse + specular * terms.specular;
}

RTWEEKEND_ENGINE_FUNCTION vec3f whitted_renderer::shade(const surface_hit& hit, const ray3f& r,
                                                        const compiled_material& m, const whitted_terms& terms,
                                                        pcg32& rng, uint64_t& rays, bool ambient) const {
    vec3f L = ambient ? terms.ambient * ambient_light_ : vec3f{0, 0, 0};
    if (lights_.empty() && environments_.empty()) return L;
    const vec3f n = hit.shading_normal, v = -r.dir;
    const shading_point sp{n, hit.front_face};
    const ray3f base = spawn(hit, hit.normal, r.dir); // origin on the side the ray came from
    for (const light_f& light : lights_) {
        ray3f shadow = base;
        vec3f l, E;
        if (light.kind == light_f::directional) {
            // Light from infinitely far along -axis: no fall-off, and anything in the way blocks it.
            l = light.axis;
            E = light.intensity;
            shadow.dir = l;
        } else {
            vec3f at = light.position;
            vec3f emitter_normal{0, 0, 0};
            float emitter_scale = 0; // mesh, sphere: the reciprocal of y's area density
            if (light.kind == light_f::area) {
                const float xi1 = rng.next_float() - 0.5f, xi2 = rng.next_float() - 0.5f;
                at = light.position + xi1 * light.edge_u + xi2 * light.edge_v;
            } else if (light.kind == light_f::mesh) {
                // A triangle by area, then a uniform point on it.
                const mesh_light_f& m = mesh_lights_[light.object];
                const double pick = rng.next_double() * m.area;
                const size_t k = std::min(m.a.size() - 1, size_t(std::upper_bound(m.cumulative_area.begin(),
                                                                                   m.cumulative_area.end(), pick) -
                                                                  m.cumulative_area.begin()));
                const float su = std::sqrt(rng.next_float()), xi = rng.next_float();
                const float b1 = su * (1 - xi), b2 = su * xi; // weights of the edges e1 and e2
                at = m.a[k] + b1 * m.e1[k] + b2 * m.e2[k];
                emitter_normal = normalize(cross(m.e1[k], m.e2[k]));
                emitter_scale = float(m.area);
            } else if (light.kind == light_f::sphere) {
                // A uniform direction on the object's sphere, carried out by the map.
                const sphere_light_f& s = sphere_lights_[light.object];
                const double z = 1 - 2 * rng.next_double(), phi = 2 * pi * rng.next_double();
                const double rxy = std::sqrt(fmax_inline(0.0, 1 - z * z));
                const vec3 dir(rxy * std::cos(phi), rxy * std::sin(phi), z);
                const vec3 n = s.normal_map * dir; // M^-T n: the world normal, unnormalised
                at = vec3f(s.linear * (s.center + s.radius * dir) + s.offset);
                emitter_normal = vec3f(unit_vector(n));
                emitter_scale = float(4 * pi * s.radius * s.radius * s.det * n.length()); // 4 pi r^2 J
            }
            vec3f to_light = at - hit.p;
            float d2 = dot(to_light, to_light);
            float d = std::sqrt(d2);
            l = to_light / d;
            E = light.intensity / d2; // irradiance at distance d: I / d^2
            if (light.kind == light_f::spot) {
                const float s = float(light.cone.falloff(double(dot(-l, light.axis))));
                if (s == 0) continue;
                E = s * E;
            } else if (light.kind == light_f::area) {
                E = (light.square_area * std::fabs(dot(light.axis, l))) * E; // L A |n_l . w_i| / d^2, two-sided
            } else if (light.kind == light_f::mesh) {
                E = (emitter_scale * std::fabs(dot(emitter_normal, l))) * E; // L A |n_y . w_i| / d^2
            } else if (light.kind == light_f::sphere) {
                const float cos_y = -dot(emitter_normal, l); // the sphere emits outwards
                if (!(cos_y > 0)) continue;
                E = (emitter_scale * cos_y) * E;
            }
            // Shadow ray towards the light; only something closer than the light blocks it (a
            // light object's own surface at y is left out, a little short of it).
            vec3f to_light_from_origin = at - shadow.origin;
            shadow.tmax = length(to_light_from_origin);
            shadow.dir = to_light_from_origin / shadow.tmax;
            if (light.kind == light_f::mesh || light.kind == light_f::sphere)
                shadow.tmax -= shadow_ray_epsilon_ + 1e-4f * shadow.tmax;
        }
        ++rays;
        if (compiled_->occluded(shadow)) continue;
        L += E * course_f_cos(m, terms, v, l, sp);
    }
    for (const environment_light& env : environments_) {
        // One direction uniform on the hemisphere about n, E = L / (1 / (2 pi)).
        const float u1 = rng.next_float(), u2 = rng.next_float();
        const vec3f l = sample_uniform_hemisphere(n, u1, u2);
        ray3f shadow = base;
        shadow.dir = l;
        ++rays;
        if (compiled_->occluded(shadow)) continue;
        L += (2 * pi_f) * env.radiance(l) * course_f_cos(m, terms, v, l, sp);
    }
    return L;
}

RTWEEKEND_ENGINE_FUNCTION bool whitted_renderer::intersect(const ray3f& r, surface_hit& hit,
                                                           const whitted_settings& w) const {
    return w.cull_back_faces ? compiled_->intersect_culling_back_faces(r, hit) : compiled_->intersect(r, hit);
}

RTWEEKEND_ENGINE_FUNCTION void whitted_renderer::material_at(surface_hit& hit, hit_material& out) const {
    // A user-written hittable reports its own material; built-in shapes index the table.
    if (hit.user_shape) {
        out.reported = compile_reported_material(hit.user_record);
        out.reported_terms = whitted_terms::of(*out.reported);
    }
    const compiled_material& stored = hit.user_shape ? *out.reported : compiled_->materials[hit.material];
    // A textured lambertian or light: its colour at this hit.
    if (stored.texture != no_texture) out.looked_up = textured(*compiled_, stored, hit);
    out.m = out.looked_up ? &*out.looked_up : &stored;
    out.terms = hit.user_shape ? &*out.reported_terms : &terms_[hit.material];
    if (out.terms->textured < 0) return;
    // A course texture map's change (course_surface_map.h).
    course_surface_map::surface mapped = textured_[size_t(out.terms->textured)].at(*compiled_, hit);
    if (mapped.normal.x != 0 || mapped.normal.y != 0 || mapped.normal.z != 0) hit.shading_normal = mapped.normal;
    out.replaced = mapped.replaced;
    out.replaced_shading = mapped.replaced_shading;
    if (!mapped.mapped) return;
    out.mapped = std::move(mapped.mapped);
    out.looked_up = out.mapped->compiled(false);
    out.mapped_terms = whitted_terms::of(*out.looked_up);
    out.m = &*out.looked_up;
    out.terms = &*out.mapped_terms;
}

// What leaves the hit point towards the ray's origin, without the delta lobes: local shading,
// and the lobes (mirror, conductor, glass) to follow while bounces remain.
RTWEEKEND_ENGINE_FUNCTION void whitted_renderer::open(surface_hit& hit, const ray3f& r, int depth, pcg32& rng,
                                                      uint64_t& rays, frame& f, const whitted_settings& w) const {
    hit_material at;
    material_at(hit, at);
    const compiled_material& m = *at.m;
    const whitted_terms& terms = *at.terms;
    // The course's rule for glass seen from inside (whitted_settings::shade_inside_dielectrics):
    // no ambient, diffuse or specular term there, and so no shadow rays.
    const bool from_inside_glass = m.refracts() && !hit.front_face;
    f.L = from_inside_glass && !w.shade_inside_dielectrics ? vec3f{0, 0, 0}
          : at.replaced                                    ? at.replaced_shading // a replace_all map
                                                           : shade(hit, r, m, terms, rng, rays);
    if (terms.emission.x != 0 || terms.emission.y != 0 || terms.emission.z != 0) f.L += terms.emission; // a light object
    f.count = f.taken = 0;
    if (depth >= max_recursion_depth_) return;

    // Where a smooth normal faces away from the viewer (at a silhouette), the mirror and refraction
    // directions are taken about the geometric normal instead.
    const vec3f wo = -r.dir;
    const vec3f n = dot(wo, hit.shading_normal) > 0 ? hit.shading_normal : hit.normal;
    const shading_point sp{n, hit.front_face};
    // Both lobes are sampled now, before either is traced. The recursion sampled transmission
    // after the reflected subtree, but a delta lobe asked for alone draws no random numbers for
    // transmission (bsdf.h), so the draws are the same.
    for (lobe which : {delta_reflection, delta_transmission}) {
        material_sample s;
        if (!m.sample(wo, sp, rng, s, which) || !s.is_delta()) continue;
        // The reflected ray stays on the side it came from; the refracted one crosses over. It
        // travels inside the object when it enters through the front or stays in at the back.
        const bool transmitted = s.sampled == delta_transmission;
        const bool inside = hit.front_face == transmitted;
        branch& b = f.branches[f.count++];
        vec3f wi = s.wi;
        if (terms.roughness > 0) {
            // The course's glossy reflection and refraction: the ideal ray tilted within a square
            // of side `roughness` about it (two random numbers per ray; a tilt that crosses the
            // surface is traced as it is, which the course leaves open).
            vec3 u, v;
            course_frame(vec3(wi.x, wi.y, wi.z), u, v);
            const float xi1 = rng.next_float() - 0.5f, xi2 = rng.next_float() - 0.5f;
            wi = normalize(wi + terms.roughness * (xi1 * vec3f(u) + xi2 * vec3f(v)));
        }
        b.ray = spawn(hit, transmitted ? -hit.normal : hit.normal, wi);
        b.weight = s.value;
        b.absorbing = inside && m.absorbs_inside();
        if (b.absorbing) b.medium = m;
    }
}

// The radiance arriving along a camera ray: the recursion L(hit) = shade + sum over lobes of
// weight x L(next hit), attenuated by Beer's law inside absorbing glass, evaluated depth first
// with an explicit stack of frames (stack[i] is the surface at depth i).
RTWEEKEND_ENGINE_FUNCTION vec3f whitted_renderer::trace(const ray3f& r, const vec3f& background, pcg32& rng,
                                                        uint64_t& rays, const whitted_settings& w) const {
    ++rays;
    surface_hit hit;
    if (!intersect(r, hit, w)) return environments_.empty() ? background : sky(r.dir);
    frame root;
    open(hit, r, 0, rng, rays, root, w);
    if (root.count == 0) return root.L;

    std::vector<frame> stack{root};
    uint32_t budget = w.max_branch_rays;
    while (true) {
        frame& f = stack.back();
        if (f.taken == f.count) {
            // Every branch of f has returned: its radiance goes to its parent.
            const vec3f out = f.attenuated ? f.attenuation * f.L : f.L;
            stack.pop_back();
            if (stack.empty()) return out;
            stack.back().L += stack.back().in_flight * out;
            continue;
        }
        const branch& b = f.branches[f.taken++];
        const vec3f weight = f.weight * b.weight;
        if (max_component(weight) < w.min_branch_weight || budget == 0) continue; // not followed
        --budget;
        ++rays;
        if (!intersect(b.ray, hit, w)) {
            f.L += b.weight * sky(b.ray.dir); // a secondary ray that leaves the scene: the environment, if any
            continue;
        }
        frame next;
        if (b.absorbing) {
            next.attenuated = true;
            next.attenuation = b.medium.transmittance(hit.t);
        }
        next.weight = next.attenuated ? weight * next.attenuation : weight;
        open(hit, b.ray, int(stack.size()), rng, rays, next, w);
        if (next.count == 0) {
            f.L += b.weight * (next.attenuated ? next.attenuation * next.L : next.L);
            continue;
        }
        f.in_flight = b.weight;
        stack.push_back(next); // f is not used after this: the vector may move
    }
}

// The course's path tracer (homework 6; docs/course.md, "Path tracing"): one path per sample, one
// indirect ray per hit. At each hit: a light object's radiance when the ray may see it (a camera
// ray, a ray from a delta lobe, any ray without next-event estimation); with next-event estimation,
// shade() without its ambient term (every light, each through a shadow ray; a ray that then hits a
// light object adds nothing, as that light was sampled); then the indirect ray: through the
// material's delta lobe when it has one (reflection or transmission chosen by Fresnel, tilted by
// its Roughness), else over the hemisphere about the shading normal, uniform (pdf 1 / (2 pi)) or,
// with importance sampling, by the cosine (pdf cos / pi), weighted by the course's f cos / pdf.
// Russian roulette continues with probability q = min(1, the throughput's largest channel) and
// divides by q, with no depth limit; without it the path stops after MaxRecursionDepth bounces.
// A path is at most whitted.max_branch_rays rays long (2^14 by default) either way.
RTWEEKEND_ENGINE_FUNCTION vec3f whitted_renderer::trace_path(const ray3f& camera_ray, const vec3f& background,
                                                             pcg32& rng, uint64_t& rays,
                                                             const view_camera::path_tracing_t& pt,
                                                             const whitted_settings& w) const {
    vec3f L{0, 0, 0}, beta{1, 1, 1};
    ray3f r = camera_ray;
    bool sees_lights = true;    // whether a light object this ray hits adds its radiance
    bool absorbing = false;     // the ray travels inside absorbing glass (`medium`)
    compiled_material medium;
    for (uint32_t depth = 0;; ++depth) {
        ++rays;
        surface_hit hit;
        if (!intersect(r, hit, w)) {
            // The environment lights, when there are any, as a light object; else the background,
            // seen by camera rays only.
            if (!environments_.empty()) {
                if (sees_lights) L += beta * sky(r.dir);
            } else if (depth == 0) {
                L += background;
            }
            break;
        }
        if (absorbing) beta *= medium.transmittance(hit.t);
        hit_material at;
        material_at(hit, at);
        const compiled_material& m = *at.m;
        const whitted_terms& terms = *at.terms;
        if (sees_lights) L += beta * terms.emission;
        // Glass seen from inside has no local shading (the classic renderer's rule).
        const bool shaded = !(m.refracts() && !hit.front_face) || w.shade_inside_dielectrics;
        if (at.replaced) L += beta * at.replaced_shading; // a replace_all map: the local shading as it gives it
        else if (pt.next_event_estimation && shaded) L += beta * shade(hit, r, m, terms, rng, rays, false);
        if (!pt.russian_roulette && depth >= uint32_t(max_recursion_depth_)) break;
        if (depth + 1 >= w.max_branch_rays) break;

        const vec3f wo = -r.dir;
        const vec3f n = dot(wo, hit.shading_normal) > 0 ? hit.shading_normal : hit.normal;
        const shading_point sp{n, hit.front_face};
        vec3f wi, weight;
        bool delta = false, transmitted = false;
        if (m.has_delta_lobe()) {
            material_sample s;
            if (!m.sample(wo, sp, rng, s, lobe(delta_reflection | delta_transmission)) || !s.is_delta()) break;
            delta = true;
            transmitted = s.sampled == delta_transmission;
            wi = s.wi;
            weight = s.value;
            if (terms.roughness > 0) {
                vec3 u, v;
                course_frame(vec3(wi.x, wi.y, wi.z), u, v);
                const float xi1 = rng.next_float() - 0.5f, xi2 = rng.next_float() - 0.5f;
                wi = normalize(wi + terms.roughness * (xi1 * vec3f(u) + xi2 * vec3f(v)));
            }
        } else {
            const float u1 = rng.next_float(), u2 = rng.next_float();
            float pdf;
            if (pt.importance_sampling) {
                wi = sample_cosine_direction(n, u1, u2);
                pdf = fmax_inline(dot(wi, n), 0.0f) * (1.0f / pi_f);
            } else {
                wi = sample_uniform_hemisphere(n, u1, u2);
                pdf = 1.0f / (2.0f * pi_f);
            }
            if (!(pdf > 0) || !(dot(wi, n) > 0)) break;
            weight = course_f_cos(m, terms, wo, wi, sp) * (1.0f / pdf);
        }
        beta *= weight;
        if (pt.russian_roulette) {
            const float q = fmin_inline(1.0f, max_component(beta));
            if (!(rng.next_float() < q)) break;
            beta *= 1.0f / q;
        }
        if (!(max_component(beta) > 0)) break;
        sees_lights = delta || !pt.next_event_estimation || !shaded;
        r = spawn(hit, transmitted ? -hit.normal : hit.normal, wi);
        // Inside glass when it enters through the front or stays in at the back.
        const bool inside = hit.front_face == transmitted;
        absorbing = delta && inside && m.absorbs_inside();
        if (absorbing) medium = m;
    }
    return L;
}

RTWEEKEND_ENGINE_FUNCTION whitted_render whitted_renderer::render(size_t camera_index,
                                                                  const render_settings& given) const {
    auto start = std::chrono::steady_clock::now();
    render_settings settings = given; // the camera's samples (one: through the centre of each pixel)
    settings.samples_per_pixel = cameras_.size() > camera_index ? std::max(1, cameras_[camera_index].samples) : 1;
    settings.first_sample = settings.end_sample = 0;
    settings.adaptive_error = 0;
    settings.check("Whitted render settings");
    if (camera_index >= cameras_.size())
        throw scene_error("camera " + std::to_string(camera_index) + " does not exist (the scene has " +
                          std::to_string(cameras_.size()) + ")");
    const view_camera& c = cameras_[camera_index];
    if (c.width <= 0 || c.height <= 0)
        throw scene_error("image resolution must be positive, got " + std::to_string(c.width) + "x" +
                          std::to_string(c.height));
    // The loader checks this too; a scene built in code reaches here unchecked.
    check_render_size(uint64_t(c.width), uint64_t(c.height), "camera " + std::to_string(camera_index) + "'s image");
    if (!finite3(c.position) || !finite3(c.gaze) || !finite3(c.up) ||
        !std::isfinite(c.left + c.right + c.bottom + c.top + c.near_distance))
        throw scene_error("camera settings must be finite numbers");

    if (!(c.aperture >= 0) || !std::isfinite(c.aperture) || (c.aperture > 0 && !(c.focus_distance > 0)) ||
        !std::isfinite(c.focus_distance))
        throw scene_error("camera aperture must be finite and non-negative, with a positive focus distance");
    // The camera's basis: w = -gaze, v' = up, u = v' x w, v = w x u (gaze and up need not be
    // perpendicular; u is normalised so that they need not be). A left-handed camera turns u round.
    const vec3 w = -unit_vector(c.gaze);
    const vec3 right_u = unit_vector(cross(c.up, w));
    const vec3 v = cross(w, right_u);
    const vec3 u = c.left_handed ? -right_u : right_u;
    if (!finite3(u) || !finite3(w)) throw scene_error("camera gaze and up must be non-zero and not parallel");
    // Pixel (i, j), j = 0 the top row: s = e - d w + (l + (i + 0.5)(r - l)/nx) u + (t - (j + 0.5)(t - b)/ny) v.
    const vec3 corner = -c.near_distance * w + c.left * u + c.top * v; // relative to e
    const vec3 du = (c.right - c.left) / c.width * u, dv = -(c.top - c.bottom) / c.height * v;
    const vec3f eye(c.position - compiled_->origin);

    const whitted_settings& ws = settings.whitted;
    // NumSamples (homework 3): sample s of a pixel is jittered in cell s of a grid x grid
    // stratification when the count is a square, else uniform in the pixel; the image is the plain
    // mean. Each draws 5 numbers, as the course says: 2 for the pixel, 2 for the lens, 1 for the
    // time. One sample through a pinhole is the pixel's centre, at time 0, drawing none.
    const int samples = settings.samples_per_pixel;
    int grid = int(std::lround(std::sqrt(double(samples))));
    if (grid * grid != samples) grid = 0;
    const double aperture = c.aperture, focus = c.focus_distance;
    render_result out = render_samples(
        c.width, c.height, settings,
        [&](int x, int y, int s, pcg32& rng, uint64_t& rays) {
            double px = 0.5, py = 0.5, lx = 0, ly = 0;
            float time = 0;
            if (samples > 1 || aperture > 0) {
                const double xi1 = rng.next_float(), xi2 = rng.next_float();
                px = grid > 0 ? (s % grid + xi1) / grid : xi1;
                py = grid > 0 ? (s / grid + xi2) / grid : xi2;
                lx = rng.next_float() - 0.5;
                ly = rng.next_float() - 0.5;
                time = rng.next_float();
            }
            vec3 dir = unit_vector(corner + (x + px) * du + (y + py) * dv);
            ray3f r;
            r.origin = eye;
            if (aperture > 0) {
                // A square lens of edge `aperture` about e; the pinhole ray's point on the plane at
                // FocusDistance along the gaze stays in focus: p = e + (focus / (dir . -w)) dir.
                const vec3 lens = aperture * (lx * u + ly * v);
                const vec3 p = (focus / dot(dir, -w)) * dir;
                r.origin = eye + vec3f(lens);
                dir = unit_vector(p - lens);
            }
            r.dir = vec3f(dir);
            r.tmin = 0;
            r.tmax = std::numeric_limits<float>::infinity();
            r.time = time;
            // A replace_background map: pixel (x, y) reads (x / nx, y / ny), the pixel's corner.
            const vec3f background =
                background_map_ ? background_map_->lookup(double(x) / c.width, double(y) / c.height) : background_;
            return c.path_tracing.on ? trace_path(r, background, rng, rays, c.path_tracing, ws)
                                     : trace(r, background, rng, rays, ws);
        },
        start);
    return {std::move(out.img), out.stats, std::move(out.sums)};
}

RTWEEKEND_ENGINE_FUNCTION whitted_render render_whitted(const whitted_scene& scene, size_t camera_index,
                                                        const render_settings& settings) {
    return whitted_renderer(scene).render(camera_index, settings);
}

RTWEEKEND_ENGINE_FUNCTION std::vector<unsigned char> encode_whitted_8bit(const image& img) {
    std::vector<unsigned char> bytes(img.data().size());
    for (size_t i = 0; i < bytes.size(); ++i) {
        float value = img.data()[i];
        bytes[i] = value >= 255.0f ? 255 : (value > 0.0f ? static_cast<unsigned char>(value) : 0); // NaN fails both
    }
    return bytes;
}

RTWEEKEND_ENGINE_FUNCTION void write_whitted_image(const std::string& path, const image& img) {
    if (img.empty()) throw scene_error("cannot write '" + path + "': the image is empty");
    const std::string ext = detail::image_format(path);
    std::string contents = ext == ".pfm"   ? encode_pfm(img)
                           : ext == ".exr" ? encode_exr(img, path)
                                           : encode_8bit_image(path, img.width(), img.height(), encode_whitted_8bit(img));
    write_file_atomically(path, contents);
}

RTWEEKEND_ENGINE_FUNCTION std::string write_course_image(const std::string& path, const image& img,
                                                         const view_camera& cam) {
    if (!cam.tonemapped) {
        write_whitted_image(path, img);
        return "";
    }
    if (img.empty()) throw scene_error("cannot write '" + path + "': the image is empty");
    const std::string ext = detail::image_format(path);
    const std::string stem = path.substr(0, path.size() - ext.size());
    const bool linear = ext == ".exr" || ext == ".pfm";
    const std::string mapped_path = linear ? stem + ".png" : path, linear_path = linear ? path : stem + ".exr";
    const std::vector<unsigned char> bytes = tonemap_photographic(img, cam.tonemap);
    // Both encoded before either is written: a failure (no OpenEXR, say) leaves neither behind.
    const std::string linear_file = detail::image_format(linear_path) == ".pfm" ? encode_pfm(img) : encode_exr(img, linear_path);
    const std::string mapped_file = encode_8bit_image(mapped_path, img.width(), img.height(), bytes);
    write_file_atomically(linear_path, linear_file);
    write_file_atomically(mapped_path, mapped_file);
    return linear ? mapped_path : linear_path;
}

#endif // RTWEEKEND_ENGINE_BODIES

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::render_whitted;
using rt::write_course_image;
using rt::whitted_render;
using rt::whitted_renderer;
#endif
