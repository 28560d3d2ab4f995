// The course's path tracer (homework 6; rtweekend/course/whitted.h, trace_path; shared/formats/
// ceng795-later.md section 11) against closed forms: a diffusely reflecting box of light meshes
// (the furnace: L_e (1 + a + a^2 + ...) summed to the depth limit, or to infinity under Russian
// roulette), a floor under a square light (kd L_e times the view factor of the square), and point
// lights, which count only through next-event estimation; and beside our own path tracer, which
// sees the same direct light and, per diffuse bounce, 1/pi of the course's indirect light (its
// units: docs/course.md). Each expectation holds for every
// combination of the renderer's parameters it names; the tolerance is five standard errors
// estimated from the spread of 16 pixels that share one expectation.

#include <rtweekend/course/whitted.h>
#include <rtweekend/io/xml_scene.h>
#include <rtweekend/render/camera_frame.h>
#include <rtweekend/render/environment.h>
#include <rtweekend/render/path_tracer.h>
#include <rtweekend/scene/scene_compiler.h>

#include <doctest/doctest.h>

#include "render_command.h"
#include "test_helpers.h"

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

namespace test_course_path {

using namespace rt;

namespace {

constexpr double pi_d = 3.14159265358979323846;

// The mean of a 4x4 image's red channel and its standard error (from the pixels' spread).
struct pixel_mean {
    double mean = 0, error = 0;
};
pixel_mean mean_of(const image& img) {
    double s = 0, s2 = 0;
    const int n = img.width() * img.height();
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) {
            const double v = img.pixel(x, y).x();
            s += v;
            s2 += v * v;
        }
    const double mean = s / n, var = std::fmax(0.0, (s2 - n * mean * mean) / (n - 1));
    return {mean, std::sqrt(var / n)};
}

std::string camera(const std::string& position, const std::string& gaze, int samples, const std::string& renderer) {
    return "<Cameras><Camera id=\"1\"><Position>" + position + "</Position><Gaze>" + gaze +
           "</Gaze><Up>0 0 1</Up><NearPlane>-0.0001 0.0001 -0.0001 0.0001</NearPlane><NearDistance>1</NearDistance>"
           "<ImageResolution>4 4</ImageResolution><ImageName>x.exr</ImageName><NumSamples>" +
           std::to_string(samples) + "</NumSamples>" + renderer + "</Camera></Cameras>";
}

std::string renderer(bool nee, bool importance, bool roulette) {
    std::string params;
    if (nee) params += " NextEventEstimation";
    if (importance) params += " ImportanceSampling";
    if (roulette) params += " RussianRoulette";
    return "<Renderer>PathTracing</Renderer><RendererParams>" + params + "</RendererParams>";
}

// A diffuse material in course units: normalised modified Phong with ks = 0 is f = kd / pi, an
// albedo of kd.
std::string diffuse_material(int id, double kd) {
    const std::string k = std::to_string(kd);
    return "<Material id=\"" + std::to_string(id) + "\" BRDF=\"1\"><DiffuseReflectance>" + k + " " + k + " " + k +
           "</DiffuseReflectance><SpecularReflectance>0 0 0</SpecularReflectance></Material>";
}
const char* diffuse_brdf = "<BRDFs><ModifiedPhong id=\"1\" normalized=\"true\"><Exponent>1</Exponent></ModifiedPhong></BRDFs>";

image render_text(const std::string& xml) {
    test::scratch_dir dir("course_path");
    const whitted_scene scene = load_xml_scene(dir.write("scene.xml", xml));
    INFO((scene.warnings.empty() ? std::string() : scene.warnings[0]));
    REQUIRE(scene.warnings.empty());
    return render_whitted(scene, 0).img;
}

// A floor (y = 0, kd 0.5) under the given <Lights>, seen at one point from `at` (direct light
// alone: MaxRecursionDepth 0).
whitted_scene lit_floor(test::scratch_dir& dir, const std::string& at, const std::string& lights) {
    return load_xml_scene(dir.write(
        "s.xml", "<Scene><MaxRecursionDepth>0</MaxRecursionDepth>" + camera(at, "0 -0.5 -0.5", 4, renderer(true, true, false)) +
                     "<Lights>" + lights + "</Lights><Materials><Material id=\"1\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance>"
                     "</Material></Materials><VertexData>-20 0 -20 20 0 -20 20 0 20 -20 0 20</VertexData><Objects>"
                     "<Mesh id=\"1\"><Material>1</Material><Faces>1 3 2 1 4 3</Faces></Mesh></Objects></Scene>"));
}

// The scene's first camera through our path tracer, with its lights as `render --integrator path`
// converts them (xml_path_compiled, xml_path_environment): the direct light alone, its mean over the pixels. Lights no
// ray hits are found by next-event estimation from the first hit (max_depth 1); an emitter the
// rays can hit is found by it and by the first hit's scattered ray, whose weights sum to one
// (multiple importance sampling), so that ray must be traced too (max_depth 2).
pixel_mean ours_direct_mean(const whitted_scene& scene, int samples, int max_depth = 1) {
    const compiled_scene compiled = app::xml_path_compiled(scene);
    render_settings settings;
    settings.samples_per_pixel = samples;
    settings.max_depth = max_depth;
    settings.quiet = true;
    return mean_of(path_trace(compiled, view_camera_frame(scene.cameras[0]), app::xml_path_environment(scene, scene.cameras[0]),
                              settings).img);
}
double ours_direct(const whitted_scene& scene) { return ours_direct_mean(scene, 4).mean; }

// t.ppm, a 4 x 2 picture whose texel (x, y) is (10 (x + 1) + 100 y, 70, 200).
void write_rows_picture(test::scratch_dir& dir) {
    std::string ppm = "P3\n4 2\n255\n";
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) ppm += std::to_string(10 * (x + 1) + 100 * y) + " 70 200\n";
    dir.write("t.ppm", ppm);
}

// The view factor from a point to a w x h rectangle in a parallel plane at distance c, the point
// below one corner (Howell's catalogue of configuration factors, B-3; the form given by Hamilton
// and Morgan 1952): F = 1/(2 pi) [A/sqrt(1+A^2) atan(B/sqrt(1+A^2)) + B/sqrt(1+B^2) atan(A/sqrt(1+B^2))].
double corner_view_factor(double w, double h, double c) {
    const double A = w / c, B = h / c;
    const double a = std::sqrt(1 + A * A), b = std::sqrt(1 + B * B);
    return (A / a * std::atan(B / a) + B / b * std::atan(A / b)) / (2 * pi_d);
}

} // namespace

TEST_CASE("course path tracer: a box of light meshes of albedo a sums L_e a^k to the depth, or all of it with roulette") {
    // A closed cube of two-sided light meshes of radiance 100 and albedo 0.5, the camera inside.
    const double Le = 100, a = 0.5;
    std::string faces;
    const int quads[6][4] = {{1, 2, 3, 4}, {5, 6, 7, 8}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 4, 8, 7}, {4, 1, 5, 8}};
    for (const auto& q : quads)
        faces += std::to_string(q[0]) + " " + std::to_string(q[1]) + " " + std::to_string(q[2]) + " " +
                 std::to_string(q[0]) + " " + std::to_string(q[2]) + " " + std::to_string(q[3]) + " ";
    auto scene = [&](int depth, const std::string& r) {
        return "<Scene><MaxRecursionDepth>" + std::to_string(depth) + "</MaxRecursionDepth>" +
               camera("0.1 0.2 0.05", "0.3 -0.2 -1", 1024, r) + diffuse_brdf + "<Materials>" + diffuse_material(1, a) +
               "</Materials><VertexData>-1 -1 -1 1 -1 -1 1 1 -1 -1 1 -1 -1 -1 1 1 -1 1 1 1 1 -1 1 1</VertexData>"
               "<Objects><LightMesh id=\"1\"><Material>1</Material><Faces>" + faces +
               "</Faces><Radiance>100 100 100</Radiance></LightMesh></Objects></Scene>";
    };
    for (bool nee : {false, true})
        for (bool importance : {false, true}) {
            CAPTURE(nee);
            CAPTURE(importance);
            // Depth 2 without roulette: the camera sees L_e, then two bounces; with next-event
            // estimation the point at depth 2 is lit directly too (a^3).
            const double capped = nee ? Le * (1 + a + a * a + a * a * a) : Le * (1 + a + a * a);
            const pixel_mean m2 = mean_of(render_text(scene(2, renderer(nee, importance, false))));
            INFO("depth 2: " << m2.mean << " +- " << m2.error << ", expected " << capped);
            CHECK(std::fabs(m2.mean - capped) <= 5 * m2.error + 1e-3 * capped);
            // Russian roulette lifts the limit: L_e / (1 - a), whatever MaxRecursionDepth says.
            const pixel_mean mr = mean_of(render_text(scene(1, renderer(nee, importance, true))));
            INFO("roulette: " << mr.mean << " +- " << mr.error << ", expected " << Le / (1 - a));
            CHECK(std::fabs(mr.mean - Le / (1 - a)) <= 5 * mr.error + 1e-3 * Le);
            CHECK(mr.error < 0.02 * Le); // the bound is not vacuous
        }
}

TEST_CASE("course path tracer: a floor under a square light is kd L_e times the square's view factor") {
    // The floor z = 0 (albedo 0.8), a black light mesh of radiance 100, 2 x 2 at height 1 centred
    // over the origin, seen from the side: the floor point at the origin receives L_e times the
    // view factor F of the square, four corner rectangles of 1 x 1 at distance 1, and reflects
    // kd L_e F.
    const double F = 4 * corner_view_factor(1, 1, 1);
    CHECK(F == doctest::Approx(0.5541).epsilon(1e-3)); // the tabulated value for a = b = c
    const double expected = 0.8 * 100 * F;
    for (bool nee : {false, true})
        for (bool importance : {false, true}) {
            CAPTURE(nee);
            CAPTURE(importance);
            const std::string xml =
                "<Scene><MaxRecursionDepth>1</MaxRecursionDepth>" + camera("3 0 0.5", "-3 0 -0.5", 4096, renderer(nee, importance, false)) +
                diffuse_brdf + "<Materials>" + diffuse_material(1, 0.8) + diffuse_material(2, 0) +
                "</Materials><VertexData>-50 -50 0 50 -50 0 50 50 0 -50 50 0 -1 -1 1 1 -1 1 1 1 1 -1 1 1</VertexData>"
                "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1 2 3 1 3 4</Faces></Mesh>"
                "<LightMesh id=\"2\"><Material>2</Material><Faces>5 7 6 5 8 7</Faces>"
                "<Radiance>100 100 100</Radiance></LightMesh></Objects></Scene>";
            const pixel_mean m = mean_of(render_text(xml));
            INFO(m.mean << " +- " << m.error << ", expected " << expected);
            CHECK(std::fabs(m.mean - expected) <= 5 * m.error + 2e-3 * expected);
            CHECK(m.error < 0.02 * expected);
        }
}

TEST_CASE("course path tracer: a point light counts through next-event estimation only, and the camera's misses see the background") {
    // A plain (level-1) floor of kd 0.6 lit by a point light of intensity 400 at height 2 above
    // the point the camera sees: I / d^2 kd cos = 100 x 0.6 = 60 with next-event estimation, 0
    // without (it is never hit); a camera turned away sees the background.
    auto scene = [](bool nee, const std::string& gaze) {
        return "<Scene><MaxRecursionDepth>3</MaxRecursionDepth><BackgroundColor>7 8 9</BackgroundColor>" +
               camera("3 0 1", gaze, 16, renderer(nee, false, false)) +
               "<Lights><PointLight id=\"1\"><Position>0 0 2</Position><Intensity>400 400 400</Intensity></PointLight></Lights>"
               "<Materials><Material id=\"1\"><DiffuseReflectance>0.6 0.6 0.6</DiffuseReflectance></Material></Materials>"
               "<VertexData>-50 -50 0 50 -50 0 50 50 0 -50 50 0</VertexData>"
               "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1 2 3 1 3 4</Faces></Mesh></Objects></Scene>";
    };
    const image lit = render_text(scene(true, "-3 0 -1"));
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) CHECK(lit.pixel(x, y).x() == doctest::Approx(60).epsilon(2e-3));
    const image dark = render_text(scene(false, "-3 0 -1"));
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) CHECK(dark.pixel(x, y).x() == 0.0f);
    const image sky = render_text(scene(true, "0 1 1"));
    CHECK(sky.pixel(1, 2).z() == 9.0f);
}

TEST_CASE("course path tracer: the reader's <Renderer> and <RendererParams>") {
    test::scratch_dir dir("course_path_reader");
    auto load = [&](const std::string& r) {
        return load_xml_scene(dir.write("s.xml", "<Scene>" + camera("0 0 5", "0 -1 -1", 1, r) +
                                                     "<VertexData>0 0 0</VertexData><Materials><Material id=\"1\"/></Materials>"
                                                     "<Objects><Sphere id=\"1\"><Material>1</Material><Center>1</Center><Radius>1</Radius></Sphere></Objects></Scene>"));
    };
    const whitted_scene s = load("<Renderer>PathTracing</Renderer><RendererParams>RussianRoulette NextEventEstimation</RendererParams>");
    CHECK(s.cameras[0].path_tracing.on);
    CHECK(s.cameras[0].path_tracing.next_event_estimation);
    CHECK(s.cameras[0].path_tracing.russian_roulette);
    CHECK_FALSE(s.cameras[0].path_tracing.importance_sampling);
    CHECK_FALSE(load("").cameras[0].path_tracing.on);
    const whitted_scene params_alone = load("<RendererParams>ImportanceSampling</RendererParams>");
    CHECK_FALSE(params_alone.cameras[0].path_tracing.on);
    REQUIRE(params_alone.warnings.size() == 1);
    CHECK(params_alone.warnings[0].find("without <Renderer>PathTracing") != std::string::npos);
    auto error_of = [&](const std::string& r) -> std::string {
        try {
            load(r);
        } catch (const scene_error& e) {
            return e.what();
        }
        return "";
    };
    CHECK(error_of("<Renderer>Photon</Renderer>").find("<Renderer> 'Photon' is not supported") != std::string::npos);
    // DirectLighting names the classic renderer, as no <Renderer> does.
    const whitted_scene direct = load("<Renderer>DirectLighting</Renderer>");
    CHECK_FALSE(direct.cameras[0].path_tracing.on);
    CHECK(direct.warnings.empty());
    CHECK(load("<Renderer>DirectLighting</Renderer><RendererParams>RussianRoulette</RendererParams>").warnings.size() == 1);
    CHECK(error_of("<Renderer>PathTracing</Renderer><RendererParams>NEE</RendererParams>").find("'NEE' is not one of") !=
          std::string::npos);
    // A plain material of kd 0.5 has the level-1 model's albedo pi kd = 1.57 in the course's path
    // tracer: under roulette its paths never end on their own. One warning; none without roulette,
    // and none for kd 0.3 (0.94).
    auto with_kd = [&](const std::string& kd, const std::string& params) {
        return load_xml_scene(dir.write("kd.xml", "<Scene>" + camera("0 0 5", "0 -1 -1", 1, "<Renderer>PathTracing</Renderer><RendererParams>" + params +
                                                                         "</RendererParams>") +
                                                      "<VertexData>0 0 0</VertexData><Materials><Material id=\"1\"><DiffuseReflectance>" + kd +
                                                      "</DiffuseReflectance></Material></Materials><Objects><Sphere id=\"1\"><Material>1</Material>"
                                                      "<Center>1</Center><Radius>1</Radius></Sphere></Objects></Scene>"));
    };
    const whitted_scene runaway = with_kd("0.5 0.2 0.2", "RussianRoulette");
    REQUIRE(runaway.warnings.size() == 1);
    CHECK(runaway.warnings[0].find("<Material id=\"1\">: reflects 1.57 times the light it receives") != std::string::npos);
    CHECK(with_kd("0.5 0.2 0.2", "NextEventEstimation").warnings.empty());
    CHECK(with_kd("0.3 0.3 0.3", "RussianRoulette").warnings.empty());
}

TEST_CASE("course path tracer: our path tracer sees the same direct light, and 1/pi of each diffuse bounce") {
    // A point light 0.3 above a floor of kd 0.5, under a black square 0.45 above the floor that hides
    // it from a ceiling of kd 0.5 at height 1. The camera looks up at the ceiling's point (2, 1, 0),
    // whose line to the light crosses the square (at x = 0.43): it is lit only by the floor.
    // Course: MaxRecursionDepth 1 (the ceiling's indirect ray, then the floor's next-event
    // estimation); ours: two rays per path, each light multiplied by pi (course intensities are pi
    // times radiometric ones: render's xml_path_lights). Level-1 materials (f = kd) are Lambertians
    // of albedo kd in ours, kd / pi of the course's f: one bounce is pi times brighter in the course.
    // On the floor, seen directly, the two must agree: kd I / d^2 cos.
    const std::string materials = "<Materials><Material id=\"1\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance></Material>"
                                  "<Material id=\"2\"><DiffuseReflectance>0 0 0</DiffuseReflectance></Material></Materials>";
    const std::string geometry =
        "<VertexData>-20 0 -20 20 0 -20 20 0 20 -20 0 20  -20 1 -20 20 1 -20 20 1 20 -20 1 20"
        "  -0.8 0.45 -0.8 0.8 0.45 -0.8 0.8 0.45 0.8 -0.8 0.45 0.8</VertexData><Objects>"
        "<Mesh id=\"1\"><Material>1</Material><Faces>1 3 2 1 4 3</Faces></Mesh>"
        "<Mesh id=\"2\"><Material>1</Material><Faces>5 6 7 5 7 8</Faces></Mesh>"
        "<Mesh id=\"3\"><Material>2</Material><Faces>9 10 11 9 11 12</Faces></Mesh></Objects>";
    const std::string light = "<Lights><PointLight id=\"1\"><Position>0 0.3 0</Position><Intensity>100 100 100</Intensity></PointLight></Lights>";
    auto both = [&](const std::string& from, const std::string& gaze, int depth, int samples) {
        test::scratch_dir dir("course_path_ours");
        const whitted_scene scene = load_xml_scene(dir.write(
            "s.xml", "<Scene><MaxRecursionDepth>" + std::to_string(depth) + "</MaxRecursionDepth>" +
                         camera(from, gaze, samples, renderer(true, true, false)) + light + materials + geometry + "</Scene>"));
        REQUIRE(scene.warnings.empty());
        const pixel_mean course = mean_of(render_whitted(scene, 0).img);
        std::vector<point_light> lights = scene.lights;
        for (point_light& l : lights) l.intensity *= pi_d;
        const compiled_scene compiled = compile_scene(scene.world, scene.cameras[0].position, lights);
        render_settings settings;
        settings.samples_per_pixel = samples;
        settings.max_depth = depth + 1;
        settings.quiet = true;
        const pixel_mean ours =
            mean_of(path_trace(compiled, view_camera_frame(scene.cameras[0]), environment::backdrop(vec3f(0, 0, 0)), settings).img);
        return std::make_pair(course, ours);
    };
    // The floor's point (1, 0, 0) from (1, 0.5, 0.5): d^2 = 1.09, cos = 0.3 / sqrt 1.09:
    // 0.5 x 100 / 1.09 x 0.2873 = 13.18, in both.
    const auto [course_direct, ours_direct] = both("1 0.5 0.5", "0 -0.5 -0.5", 0, 16);
    const double direct = 0.5 * 100 / 1.09 * (0.3 / std::sqrt(1.09));
    CHECK(course_direct.mean == doctest::Approx(direct).epsilon(1e-3));
    CHECK(ours_direct.mean == doctest::Approx(direct).epsilon(1e-3));
    // The ceiling: the course's mean is pi times ours, within five standard errors of each.
    const auto [course_indirect, ours_indirect] = both("2 0.5 0", "0 1 0", 1, 4096);
    INFO(course_indirect.mean << " +- " << course_indirect.error << ", ours x pi " << pi_d * ours_indirect.mean << " +- "
                              << pi_d * ours_indirect.error);
    CHECK(course_indirect.mean > 0.1);
    CHECK(std::fabs(course_indirect.mean - pi_d * ours_indirect.mean) <=
          5 * std::hypot(course_indirect.error, pi_d * ours_indirect.error));
    CHECK(course_indirect.error < 0.03 * course_indirect.mean);
}

TEST_CASE("course path tracer: a directional light on a floor, kd E cos in the course's and in ours") {
    // Light travelling along (1, -2, 0) over a floor of kd 0.5: cos = 2 / sqrt 5 everywhere, so the
    // point (1, 0, 0) seen directly is 0.5 x 10 x 0.8944 = 4.472, in the course's path tracer and in
    // ours with E multiplied by pi (render's xml_path_directional_lights).
    test::scratch_dir dir("course_path_sun");
    const whitted_scene scene = lit_floor(dir, "1 0.5 0.5", "<DirectionalLight id=\"1\"><Direction>1 -2 0</Direction>"
                                                              "<Radiance>10 10 10</Radiance></DirectionalLight>");
    REQUIRE(scene.warnings.empty());
    REQUIRE(scene.directional_lights.size() == 1);
    const double expected = 0.5 * 10 * 2 / std::sqrt(5.0);
    CHECK(mean_of(render_whitted(scene, 0).img).mean == doctest::Approx(expected).epsilon(1e-4));
    CHECK(ours_direct(scene) == doctest::Approx(expected).epsilon(1e-4));
}

TEST_CASE("course path tracer: a spot light on a floor, inside, between and outside its cones, in both") {
    // A spot 2 above the floor (kd 0.5) shining down, intensity 100, coverage 60 and falloff 30
    // degrees (full angles): at the floor point at angle theta from the axis, d = 2 / cos theta,
    // so kd I s(theta) cos^3 theta / 4 with s = 1 within 15 degrees, 0 beyond 30, and
    // ((cos theta - cos 30) / (cos 15 - cos 30))^4 between: in the course's path tracer, and in
    // ours with the spot as render's xml_path_lights makes it (a point light with a cone,
    // intensity times pi, cone exponent 4).
    const double deg = pi_d / 180;
    auto expected = [&](double theta) {
        const double c = std::cos(theta), c15 = std::cos(15 * deg), c30 = std::cos(30 * deg);
        const double s = c >= c15 ? 1 : c < c30 ? 0 : std::pow((c - c30) / (c15 - c30), 4);
        return 0.5 * 100 * s * c * c * c / 4;
    };
    for (double theta_deg : {0.0, 10.0, 20.0, 25.0, 40.0}) {
        CAPTURE(theta_deg);
        const double x = 2 * std::tan(theta_deg * deg);
        test::scratch_dir dir("course_path_spot");
        const whitted_scene scene =
            lit_floor(dir, std::to_string(x) + " 0.5 0.5",
                      "<SpotLight id=\"1\"><Position>0 2 0</Position><Direction>0 -1 0</Direction><Intensity>100 100 100</Intensity>"
                      "<CoverageAngle>60</CoverageAngle><FalloffAngle>30</FalloffAngle></SpotLight>");
        REQUIRE(scene.warnings.empty());
        REQUIRE(scene.spot_lights.size() == 1);
        const double want = expected(theta_deg * deg);
        CHECK(mean_of(render_whitted(scene, 0).img).mean == doctest::Approx(want).epsilon(2e-3));
        CHECK(ours_direct(scene) == doctest::Approx(want).epsilon(2e-3));
    }
}

TEST_CASE("course path tracer: an area light over a floor, kd L pi F in both, and no ray sees it") {
    // A square <AreaLight> of size 2 and radiance 100 at height 1 over the floor's point the
    // camera sees: irradiance L pi F with F = 4 x the corner view factor (0.5541), so kd L pi F
    // (kd 0.5) in the course's units (f = kd), and the same in ours (radiance times pi, f = kd / pi),
    // the light found by next-event estimation alone. Two-sided: the same with its normal turned.
    const double expected = 0.5 * 100 * pi_d * 4 * corner_view_factor(1, 1, 1);
    for (const char* normal : {"0 -1 0", "0 1 0"}) {
        CAPTURE(normal);
        test::scratch_dir dir("course_path_area");
        const whitted_scene scene =
            lit_floor(dir, "0 0.5 0.5",
                      std::string("<AreaLight id=\"1\"><Position>0 1 0</Position><Normal>") + normal +
                          "</Normal><Size>2</Size><Radiance>100 100 100</Radiance></AreaLight>");
        REQUIRE(scene.warnings.empty());
        REQUIRE(scene.area_lights.size() == 1);
        const pixel_mean ours = ours_direct_mean(scene, 1024);
        INFO(ours.mean << " +- " << ours.error << ", expected " << expected);
        CHECK(std::fabs(ours.mean - expected) <= 5 * ours.error + 2e-3 * expected);
        CHECK(ours.error < 0.02 * expected);
        const pixel_mean course = mean_of(render_whitted(scene, 0).img);
        CHECK(std::fabs(course.mean - expected) <= 5 * course.error + 0.02 * expected);
    }
    // Hidden from camera rays: a small square across the camera's ray, facing it (radiance times
    // pi would show 314 there); the camera sees through it the floor it lights, some 8.
    test::scratch_dir dir("course_path_area_seen");
    const whitted_scene across = lit_floor(dir, "0 0.5 0.5", "<AreaLight id=\"1\"><Position>0 0.25 0.25</Position>"
                                                           "<Normal>0 1 1</Normal><Size>0.2</Size><Radiance>100 100 100</Radiance></AreaLight>");
    const double seen = ours_direct(across);
    CHECK(seen > 1);
    CHECK(seen < 20);
}

TEST_CASE("course path tracer: light meshes and spheres in ours, as bright as in the course's, and seen") {
    // The floor (kd 0.5) under a <LightMesh> square of size 2 and radiance 100 at height 1: the
    // area light's kd L pi F (above), in the Whitted integrator and in ours (a two-sided
    // diffuse_light of L times pi, light-sampled). Under a <LightSphere> of radius 0.25 whose
    // centre is 1 above the seen point: irradiance pi L' (r / h)^2 (the whole sphere above the
    // horizon), so kd pi L (r / h)^2 in both units.
    auto scene_with = [](test::scratch_dir& dir, const std::string& at, const std::string& gaze, const std::string& light,
                         const std::string& transformations = "") {
        return load_xml_scene(dir.write(
            "s.xml", "<Scene>" + transformations + "<MaxRecursionDepth>0</MaxRecursionDepth>" + camera(at, gaze, 4, "") +
                         "<Materials><Material id=\"1\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance></Material>"
                         "<Material id=\"2\"><DiffuseReflectance>0 0 0</DiffuseReflectance></Material></Materials>"
                         "<VertexData>-20 0 -20 20 0 -20 20 0 20 -20 0 20  -1 1 -1 1 1 -1 1 1 1 -1 1 1  0 1 0</VertexData><Objects>"
                         "<Mesh id=\"1\"><Material>1</Material><Faces>1 3 2 1 4 3</Faces></Mesh>" + light + "</Objects></Scene>"));
    };
    const std::string square = "<LightMesh id=\"1\"><Material>2</Material><Faces>5 6 7 5 7 8</Faces><Radiance>100 100 100</Radiance></LightMesh>";
    const std::string ball = "<LightSphere id=\"1\"><Material>2</Material><Center>9</Center><Radius>0.25</Radius><Radiance>100 100 100</Radiance></LightSphere>";
    const std::string ball_scaled = "<LightSphere id=\"1\"><Material>2</Material><Center>9</Center><Radius>0.125</Radius>"
                                    "<Transformations>s1</Transformations><Radiance>100 100 100</Radiance></LightSphere>";
    struct lit {
        std::string light, transformations;
        double expected;
    };
    const double r = 0.25;
    for (const lit& c : {lit{square, "", 0.5 * 100 * pi_d * 4 * corner_view_factor(1, 1, 1)},
                         lit{ball, "", 0.5 * pi_d * 100 * r * r},
                         // Radius 0.125 scaled by 2 about the origin: the centre moves to height 2,
                         // the sphere is radius 0.25 there.
                         lit{ball_scaled, "<Transformations><Scaling id=\"1\">2 2 2</Scaling></Transformations>",
                             0.5 * pi_d * 100 * r * r / 4}}) {
        CAPTURE(c.light);
        test::scratch_dir dir("course_path_objects");
        const whitted_scene scene = scene_with(dir, "0 0.5 0.5", "0 -0.5 -0.5", c.light, c.transformations);
        INFO((scene.warnings.empty() ? std::string() : scene.warnings[0]));
        REQUIRE(scene.warnings.empty());
        REQUIRE(scene.light_meshes.size() + scene.light_spheres.size() == 1);
        const pixel_mean ours = ours_direct_mean(scene, 1024, 2);
        INFO(ours.mean << " +- " << ours.error << ", expected " << c.expected);
        CHECK(std::fabs(ours.mean - c.expected) <= 5 * ours.error + 2e-3 * c.expected);
        CHECK(ours.error < 0.02 * c.expected);
        const pixel_mean course = mean_of(render_whitted(scene, 0).img);
        CHECK(std::fabs(course.mean - c.expected) <= 5 * course.error + 0.02 * c.expected);
    }
    // Seen from below and from above, the square shows L times pi in ours (two-sided), L in the
    // course's (its units: docs/course.md).
    for (const auto& [from, gaze] : {std::pair<const char*, const char*>{"0 0.5 0", "0 1 0"}, {"0 1.5 0", "0 -1 0"}}) {
        CAPTURE(from);
        test::scratch_dir dir("course_path_objects_seen");
        const whitted_scene scene = scene_with(dir, from, gaze, square);
        CHECK(ours_direct_mean(scene, 4, 2).mean == doctest::Approx(100 * pi_d).epsilon(1e-5));
        CHECK(mean_of(render_whitted(scene, 0).img).mean == doctest::Approx(100).epsilon(1e-5));
    }
}

TEST_CASE("course path tracer: an environment light in ours, a floor pi kd L as in the course's") {
    // A floor z = 0 of kd 0.5 under a lat-long sky of 100 everywhere (a 4 x 2 PFM): pi kd L = 157.1
    // in the course's units (test_course_environment.cpp), and in ours with the sky's radiance
    // times pi, light-sampled (render's xml_path_environment). The camera sees nothing else.
    test::scratch_dir dir("course_path_env");
    std::string pfm = "PF\n4 2\n-1\n";
    for (int i = 0; i < 4 * 2 * 3; ++i) {
        const float v = 100;
        pfm += std::string(reinterpret_cast<const char*>(&v), 4);
    }
    dir.write("grey.pfm", pfm);
    auto scene_with = [&](const std::string& lights) {
        return load_xml_scene(dir.write(
            "s.xml", "<Scene><MaxRecursionDepth>0</MaxRecursionDepth>" + camera("1 0 1", "-1 0 -1", 4, "") +
                         "<Textures><Images><Image id=\"1\">grey.pfm</Image></Images></Textures><Lights>" + lights +
                         "</Lights><Materials><Material id=\"1\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance></Material></Materials>"
                         "<VertexData>-50 -50 0 50 -50 0 50 50 0 -50 50 0</VertexData><Objects><Mesh id=\"1\"><Material>1</Material>"
                         "<Faces>1 2 3 1 3 4</Faces></Mesh></Objects></Scene>"));
    };
    const std::string sky = "<SphericalDirectionalLight id=\"1\"><ImageId>1</ImageId></SphericalDirectionalLight>";
    const whitted_scene scene = scene_with(sky);
    REQUIRE(scene.warnings.empty());
    const pixel_mean ours = ours_direct_mean(scene, 256, 2);
    INFO(ours.mean << " +- " << ours.error);
    CHECK(std::fabs(ours.mean - pi_d * 0.5 * 100) <= 5 * ours.error + 1e-3 * pi_d * 50);
    CHECK(ours.error < 0.01 * pi_d * 50);
    // Two environment lights: one line.
    test::check_scene_error([&] { app::check_xml_path_scene("s.xml", scene_with(sky + sky)); },
                            {"s.xml", "--integrator path takes one environment light; this scene has 2"});
}

TEST_CASE("course path tracer: texture maps in ours, the same direct light as the course's") {
    // The course's texture maps looked up in ours at each hit (render's xml_path_compiled: a
    // course_surface_map per textured object): at points of a textured square and of a sphere, a
    // point light's direct light is the Whitted integrator's, kd I cos / d^2 with the maps' kd and
    // normal. Both see one point: a near plane of 1e-4. First the colour maps: an image (nearest)
    // on the square, a checkerboard in the sphere's object space, blended with kd.
    test::scratch_dir dir("course_path_textures");
    write_rows_picture(dir);
    auto scene_at = [&](const std::string& from, const std::string& gaze, const std::string& ks, const std::string& maps,
                        const std::string& objects) {
        return load_xml_scene(dir.write(
            "s.xml", "<Scene><MaxRecursionDepth>0</MaxRecursionDepth><Cameras><Camera id=\"1\"><Position>" + from +
                         "</Position><Gaze>" + gaze + "</Gaze><Up>0 1 0</Up><NearPlane>-0.0001 0.0001 -0.0001 0.0001</NearPlane>"
                         "<NearDistance>1</NearDistance><ImageResolution>4 4</ImageResolution><ImageName>x.png</ImageName>"
                         "</Camera></Cameras><Lights><PointLight id=\"1\"><Position>0.3 0.2 2</Position><Intensity>10 10 10</Intensity></PointLight></Lights>"
                         "<Materials><Material id=\"1\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance><SpecularReflectance>" +
                         ks + "</SpecularReflectance><PhongExponent>10</PhongExponent></Material></Materials>"
                         "<Textures><Images><Image id=\"1\">t.ppm</Image></Images>" + maps + "</Textures>" + objects + "</Scene>"));
    };
    const std::string image_map = "<TextureMap id=\"1\" type=\"image\"><ImageId>1</ImageId><DecalMode>replace_kd</DecalMode></TextureMap>";
    const std::string checker = "<TextureMap id=\"1\" type=\"checkerboard\"><DecalMode>blend_kd</DecalMode><BlackColor>0 0 0</BlackColor>"
                                "<WhiteColor>1 1 1</WhiteColor><Scale>2</Scale><Offset>0.01</Offset></TextureMap>";
    const std::string square = "<VertexData>-1 -1 0 1 -1 0 1 1 0 -1 1 0</VertexData><TexCoordData>0 1 1 1 1 0 0 0</TexCoordData>"
                               "<Objects><Mesh id=\"1\"><Material>1</Material><Textures>1</Textures><Faces>1 2 3 1 3 4</Faces></Mesh></Objects>";
    const std::string ball = "<VertexData>0 0 0</VertexData><Objects><Sphere id=\"1\"><Material>1</Material><Textures>1</Textures>"
                             "<Center>1</Center><Radius>1</Radius></Sphere></Objects>";
    struct probe {
        const char* from;
        const char* gaze;
        const std::string& maps;
        const std::string& objects;
    };
    for (const probe& p : {probe{"-0.6 0.7 3", "0 0 -1", image_map, square}, probe{"0.8 -0.3 3", "0 0 -1", image_map, square},
                           probe{"0.1 0.2 3", "0 0 -1", image_map, square}, probe{"0.2 0.3 3", "0 0 -1", checker, ball},
                           probe{"-0.4 0.1 3", "0 0 -1", checker, ball}, probe{"0.5 -0.6 3", "0 0 -1", checker, ball}}) {
        CAPTURE(p.from);
        const whitted_scene scene = scene_at(p.from, p.gaze, "0 0 0", p.maps, p.objects);
        REQUIRE(scene.warnings.empty());
        REQUIRE(scene.textured_objects.size() == 1);
        app::check_xml_path_scene("s.xml", scene);
        const double course = mean_of(render_whitted(scene, 0).img).mean;
        CHECK(course > 0.01);
        CHECK(ours_direct(scene) == doctest::Approx(course).epsilon(1e-4));
    }
    // With a specular colour the material is blinn_phong, whose glossy lobe is ours, not the
    // course's, and whose diffuse lobe takes the texture. At two points placed symmetrically about
    // the light's foot (0.3, 0.2), each seen from straight above, the glossy lobe adds the same,
    // though their texels differ (red 20 and 140): what ks 0.2 adds over ks 0 is equal at both.
    auto glossy_at = [&](const char* from) {
        return ours_direct(scene_at(from, "0 0 -1", "0.2 0.2 0.2", image_map, square)) -
               ours_direct(scene_at(from, "0 0 -1", "0 0 0", image_map, square));
    };
    const double glossy = glossy_at("-0.3 0.7 3");
    CHECK(glossy > 0.001);
    CHECK(glossy_at("0.9 -0.3 3") == doctest::Approx(glossy).epsilon(1e-3));
    CHECK(ours_direct(scene_at("-0.3 0.7 3", "0 0 -1", "0 0 0", image_map, square)) !=
          doctest::Approx(ours_direct(scene_at("0.9 -0.3 3", "0 0 -1", "0 0 0", image_map, square))));
    // A mesh's normal map (replace_normal): one texel, (218, 128, 218), the normal 2 c / 255 - 1 =
    // (0.71, 0.004, 0.71) in (T, B, N) = (dP/du, dP/dv, n), tilted towards +x on the square as it
    // is and towards +y on the square turned 90 degrees about z: the same light as the course's.
    dir.write("n.ppm", "P3\n1 1\n255\n218 128 218\n");
    const std::string normal_map = "<Images><Image id=\"2\">n.ppm</Image></Images><TextureMap id=\"1\" type=\"image\"><ImageId>2</ImageId>"
                                   "<DecalMode>replace_normal</DecalMode></TextureMap>";
    const std::string turned = "<Transformations><Rotation id=\"1\">90 0 0 1</Rotation></Transformations>" +
                               std::string(square).replace(square.find("<Faces>"), 0, "<Transformations>r1</Transformations>");
    for (const std::string* objects : {&square, &turned})
        for (const char* from : {"-0.6 0.7 3", "0.8 -0.3 3"}) {
            CAPTURE(from);
            const whitted_scene scene = scene_at(from, "0 0 -1", "0 0 0", normal_map, *objects);
            REQUIRE(scene.warnings.empty());
            app::check_xml_path_scene("s.xml", scene);
            const double course = mean_of(render_whitted(scene, 0).img).mean;
            CHECK(course > 0.01);
            CHECK(ours_direct(scene) == doctest::Approx(course).epsilon(1e-4));
        }
    // Every other decal, through the surface map the path tracer asks at each hit
    // (course_surface_map.h): a normal map on the sphere (in its world-space frame), bump maps
    // from the image (on the square) and from Perlin noise (on the sphere): the course's light.
    const std::string bump_image = "<TextureMap id=\"1\" type=\"image\"><ImageId>1</ImageId><DecalMode>bump_normal</DecalMode>"
                                   "<BumpFactor>0.02</BumpFactor></TextureMap>";
    const std::string bump_noise = "<TextureMap id=\"1\" type=\"perlin\"><DecalMode>bump_normal</DecalMode>"
                                   "<NoiseScale>3</NoiseScale><BumpFactor>0.3</BumpFactor></TextureMap>";
    // (Points near the light's foot: where a tilted normal sees the light's mirror image through
    // the surface too, ours adds it, as its fold of smooth normals does, vertex_material.h, and
    // the course's does not.)
    for (const probe& p : {probe{"0.2 0.3 3", "0 0 -1", normal_map, ball}, probe{"0.35 0.1 3", "0 0 -1", normal_map, ball},
                           probe{"-0.6 0.7 3", "0 0 -1", bump_image, square}, probe{"0.1 0.6 3", "0 0 -1", bump_image, square},
                           probe{"0.2 0.3 3", "0 0 -1", bump_noise, ball}, probe{"-0.4 0.1 3", "0 0 -1", bump_noise, ball}}) {
        CAPTURE(p.from);
        CAPTURE(p.maps);
        const whitted_scene scene = scene_at(p.from, p.gaze, "0 0 0", p.maps, p.objects);
        REQUIRE(scene.warnings.empty());
        app::check_xml_path_scene("s.xml", scene);
        const double course = mean_of(render_whitted(scene, 0).img).mean;
        CHECK(course > 0.01);
        CHECK(ours_direct(scene) == doctest::Approx(course).epsilon(1e-4));
        // The map matters: without it the light differs.
        std::string bare = p.objects;
        bare.erase(bare.find("<Textures>1</Textures>"), 22);
        CHECK(ours_direct(scene_at(p.from, p.gaze, "0 0 0", "", bare)) != doctest::Approx(course).epsilon(1e-3));
    }
    // replace_ks: at (0.8, -0.3) the square's texel is (140, 70, 200), so ks = texel / 255 there:
    // the light of the same material with that ks and no map, which differs from ks = 0's.
    std::string plain_square = square;
    plain_square.erase(plain_square.find("<Textures>1</Textures>"), 22);
    std::string ks_map = image_map;
    ks_map.replace(ks_map.find("replace_kd"), 10, "replace_ks");
    const double ks_mapped = ours_direct(scene_at("0.8 -0.3 3", "0 0 -1", "0 0 0", ks_map, square));
    const double ks_given = ours_direct(scene_at("0.8 -0.3 3", "0 0 -1", "0.5490196 0.2745098 0.7843137", "", plain_square));
    CHECK(ks_mapped == doctest::Approx(ks_given).epsilon(1e-4));
    CHECK(ks_mapped > 1.001 * ours_direct(scene_at("0.8 -0.3 3", "0 0 -1", "0 0 0", "", plain_square)));
    // replace_all: the surface shows texel / 255 (red 140 there), unlit, in both renderers.
    std::string all_map = image_map;
    all_map.replace(all_map.find("replace_kd"), 10, "replace_all");
    const whitted_scene shown = scene_at("0.8 -0.3 3", "0 0 -1", "0.2 0.2 0.2", all_map, square);
    CHECK(ours_direct(shown) == doctest::Approx(140.0 / 255).epsilon(1e-6));
    CHECK(mean_of(render_whitted(shown, 0).img).mean == doctest::Approx(140.0 / 255).epsilon(1e-6));
    // kd maps on a mirror (its diffuse base) and on a BRDF material (its kd): the course's light.
    for (const char* material : {"<MirrorReflectance>0.5 0.5 0.5</MirrorReflectance>", "BRDF"}) {
        CAPTURE(material);
        for (const char* from : {"-0.6 0.7 3", "0.8 -0.3 3"}) {
            // (A mirror's Blinn-Phong highlight is the course's alone: ks 0 there.)
            const bool brdf = std::string(material) == "BRDF";
            scene_at(from, "0 0 -1", brdf ? "0.3 0.3 0.3" : "0 0 0", image_map, square); // writes s.xml
            const whitted_scene scene = [&] {
                std::ifstream in(dir.path / "s.xml");
                std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
                if (brdf) {
                    text.replace(text.find("<Material id=\"1\">"), 17, "<Material id=\"1\" BRDF=\"1\">");
                    text.replace(text.find("<Materials>"), 0,
                                 "<BRDFs><ModifiedBlinnPhong id=\"1\" normalized=\"true\"><Exponent>10</Exponent></ModifiedBlinnPhong></BRDFs>");
                } else {
                    text.replace(text.find("</Material>"), 0, material);
                    text.replace(text.find("<Material id=\"1\">"), 17, "<Material id=\"1\" type=\"mirror\">");
                }
                return load_xml_scene(dir.write("s.xml", text));
            }();
            INFO((scene.warnings.empty() ? std::string() : scene.warnings[0]));
            REQUIRE(scene.warnings.empty());
            REQUIRE(scene.textured_objects.size() == 1);
            const double course = mean_of(render_whitted(scene, 0).img).mean;
            CHECK(course > 0.01);
            CHECK(ours_direct(scene) == doctest::Approx(course).epsilon(1e-4));
        }
    }
}

TEST_CASE("course path tracer: a background image, pixel (x, y) reading (x / nx, y / ny), as in the course's") {
    // A 4 x 2 picture behind a film of 8 x 4 with nothing in view: pixel (x, y) shows texel
    // (floor(x / 2), floor(y / 2)) by nearest lookup, as it is (0-255 units), in ours and in the
    // Whitted integrator; the rays that leave after a bounce see black.
    test::scratch_dir dir("course_path_background");
    write_rows_picture(dir);
    const whitted_scene scene = load_xml_scene(dir.write(
        "s.xml", "<Scene><BackgroundColor>5 5 5</BackgroundColor><Cameras><Camera id=\"1\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze>"
                 "<Up>0 1 0</Up><NearPlane>-1 1 -0.5 0.5</NearPlane><NearDistance>1</NearDistance><ImageResolution>8 4</ImageResolution>"
                 "<ImageName>x.png</ImageName></Camera></Cameras><Materials><Material id=\"1\"><DiffuseReflectance>1 1 1</DiffuseReflectance>"
                 "</Material></Materials><Textures><Images><Image id=\"1\">t.ppm</Image></Images><TextureMap id=\"1\" type=\"image\">"
                 "<ImageId>1</ImageId><DecalMode>replace_background</DecalMode></TextureMap></Textures><VertexData>0 0 10</VertexData>"
                 "<Objects><Sphere id=\"1\"><Material>1</Material><Center>1</Center><Radius>1</Radius></Sphere></Objects></Scene>"));
    REQUIRE(scene.warnings.empty());
    REQUIRE(scene.background_texture);
    app::check_xml_path_scene("s.xml", scene);
    render_settings settings;
    settings.samples_per_pixel = 4;
    settings.quiet = true;
    const image ours = path_trace(app::xml_path_compiled(scene), view_camera_frame(scene.cameras[0]),
                                  app::xml_path_environment(scene, scene.cameras[0]), settings).img;
    const image course = render_whitted(scene, 0).img;
    REQUIRE(ours.width() == 8);
    REQUIRE(ours.height() == 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) {
            CAPTURE(x);
            CAPTURE(y);
            const color expected(10 * (x / 2 + 1) + 100 * (y / 2), 70, 200);
            for (const image* img : {&ours, &course}) {
                CHECK(img->pixel(x, y).x() == doctest::Approx(expected.x()).epsilon(1e-6));
                CHECK(img->pixel(x, y).y() == doctest::Approx(expected.y()).epsilon(1e-6));
                CHECK(img->pixel(x, y).z() == doctest::Approx(expected.z()).epsilon(1e-6));
            }
        }
}

} // namespace test_course_path
