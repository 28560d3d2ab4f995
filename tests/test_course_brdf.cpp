// The CENG795 course's BRDFs (homework 6; rtweekend/core/materials/course_brdf_bsdf.h,
// shared/formats/ceng795-later.md section 10): each model's f cos theta_i at chosen angles, worked
// out from the angles in degrees (not from the vectors the code sees); the <BRDFs> section read
// from XML; and the classic renderer's pixel on a floor under a point light, I / d^2 f cos theta_i.

#include <rtweekend/course/whitted.h>
#include <rtweekend/io/xml_scene.h>
#include <rtweekend/whitted_material.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <cmath>
#include <string>

namespace test_course_brdf {

using namespace rt;

namespace {

constexpr double pi_d = 3.14159265358979323846;
double deg(double d) { return d * pi_d / 180; }

// The angles of the test: n = +z; wi 60 degrees from n towards +x, wo 30 degrees from n towards
// -x (both in the xz plane). Then theta_i = 60, theta_o = 30; wi's mirror image lies 60 degrees
// towards -x, 30 degrees from wo (alpha_r = 30); the half vector lies half way, 15 degrees towards
// +x (alpha_h = 15), 45 degrees from wo and wi.
const vec3f n_f{0, 0, 1};
const vec3f wi_f{float(std::sin(deg(60))), 0, float(std::cos(deg(60)))};
const vec3f wo_f{float(-std::sin(deg(30))), 0, float(std::cos(deg(30)))};
const double cos_i = std::cos(deg(60)), cos_o = std::cos(deg(30));
const double cos_r = std::cos(deg(30)), cos_h = std::cos(deg(15)), wo_h = std::cos(deg(45));
const double kd = 0.5, ks = 0.25, p = 10;

// Fresnel reflectance of glass of index 1.5 at 60 degrees, from Snell's law and the Fresnel
// equations (the conductor formula with k = 0 reduces to these).
double fresnel_glass_60() {
    const double eta = 1.5, ct = std::sqrt(1 - std::pow(std::sin(deg(60)) / eta, 2));
    const double rs = (cos_i - eta * ct) / (cos_i + eta * ct), rp = (eta * cos_i - ct) / (eta * cos_i + ct);
    return 0.5 * (rs * rs + rp * rp);
}

course_brdf_bsdf make(course_brdf_bsdf::model_t m, bool normalized = false, bool kd_fresnel = false) {
    course_brdf_bsdf b;
    b.model = m;
    b.normalized = normalized;
    b.kd_fresnel = kd_fresnel;
    b.kd = {float(kd), float(kd), float(kd)};
    b.ks = {float(ks), float(ks), float(ks)};
    b.exponent = float(p);
    b.eta = 1.5f;
    b.k = 0;
    return b;
}

struct expectation {
    const char* name;
    course_brdf_bsdf brdf;
    double value; // f cos theta_i
};

std::vector<expectation> expectations() {
    using m = course_brdf_bsdf::model_t;
    const double F = fresnel_glass_60();
    const double D = (p + 2) / (2 * pi_d) * std::pow(cos_h, p);
    // G = min(1, 2 (n.h)(n.wo)/(wo.h), 2 (n.h)(n.wi)/(wo.h)) = min(1, 2.37, 1.37) = 1.
    const double G = std::fmin(1, std::fmin(2 * cos_h * cos_o / wo_h, 2 * cos_h * cos_i / wo_h));
    const double specular_ts = ks * D * F * G / (4 * cos_i * cos_o);
    return {
        {"OriginalPhong", make(m::original_phong), (kd + ks * std::pow(cos_r, p) / cos_i) * cos_i},
        {"ModifiedPhong", make(m::modified_phong), (kd + ks * std::pow(cos_r, p)) * cos_i},
        {"ModifiedPhong normalized", make(m::modified_phong, true),
         (kd / pi_d + ks * (p + 2) / (2 * pi_d) * std::pow(cos_r, p)) * cos_i},
        {"OriginalBlinnPhong", make(m::original_blinn_phong), (kd + ks * std::pow(cos_h, p) / cos_i) * cos_i},
        {"ModifiedBlinnPhong", make(m::modified_blinn_phong), (kd + ks * std::pow(cos_h, p)) * cos_i},
        {"ModifiedBlinnPhong normalized", make(m::modified_blinn_phong, true),
         (kd / pi_d + ks * (p + 8) / (8 * pi_d) * std::pow(cos_h, p)) * cos_i},
        {"TorranceSparrow", make(m::torrance_sparrow), (kd / pi_d + specular_ts) * cos_i},
        {"TorranceSparrow kdfresnel", make(m::torrance_sparrow, false, true),
         ((1 - F) * kd / pi_d + specular_ts) * cos_i},
    };
}

} // namespace

TEST_CASE("course BRDFs: f cos theta_i of each model at chosen angles") {
    // The test's own numbers, once: the mirror and half-vector angles as the geometry says.
    CHECK(std::fabs(std::pow(cos_r, 10) - 0.2373046875) < 1e-12); // cos^10 30 = (3/4)^5
    CHECK(std::fabs(fresnel_glass_60() - 0.0891867) < 1e-6);
    for (const expectation& e : expectations()) {
        CAPTURE(e.name);
        const vec3f v = e.brdf.course_value(wo_f, wi_f, n_f);
        CHECK(v.x == doctest::Approx(e.value).epsilon(2e-6));
        CHECK(v.y == v.x);
        // eval is the same over pi (course units: a Lambertian kd is an albedo, f = kd / pi).
        const vec3f f = e.brdf.eval(wo_f, wi_f, shading_point{n_f, true});
        CHECK(f.x == doctest::Approx(e.value / pi_d).epsilon(2e-6));
        // Light from below the surface: 0.
        const vec3f below = e.brdf.course_value(wo_f, vec3f{wi_f.x, 0, -wi_f.z}, n_f);
        CHECK(below.x == 0);
    }
}

TEST_CASE("course BRDFs: without ks only the diffuse term, channel by channel") {
    // The diffuse term alone, by hand: kd cos theta_i, or kd / pi cos theta_i for the normalised
    // and Torrance-Sparrow models ((1 - F) kd / pi cos theta_i with kdfresnel).
    const double F = fresnel_glass_60();
    const double diffuse[] = {kd * cos_i, kd * cos_i, kd / pi_d * cos_i, kd * cos_i,
                              kd * cos_i, kd / pi_d * cos_i, kd / pi_d * cos_i, (1 - F) * kd / pi_d * cos_i};
    size_t k = 0;
    for (const expectation& e : expectations()) {
        CAPTURE(e.name);
        course_brdf_bsdf none = e.brdf, blue = e.brdf;
        none.ks = {0, 0, 0};
        blue.ks = {0, 0, float(ks)}; // glossy in one channel: the power is still taken for it
        const vec3f v = none.course_value(wo_f, wi_f, n_f), b = blue.course_value(wo_f, wi_f, n_f);
        CHECK(v.x == doctest::Approx(diffuse[k]).epsilon(2e-6));
        CHECK((v.y == v.x && v.z == v.x));
        CHECK((b.x == v.x && b.y == v.x));
        CHECK(b.z == doctest::Approx(e.value).epsilon(2e-6));
        ++k;
    }
    CHECK(k == 8);
}

TEST_CASE("course BRDFs: read from <BRDFs> and rendered on a floor as I / d^2 f cos theta_i") {
    // A floor z = 0; the light 2 units from the origin along wi, intensity 1000 (E = 250); a 1x1
    // camera on wo's line looking at the origin (its one ray is the gaze).
    const char* models[] = {"<OriginalPhong id=\"1\">", "<ModifiedPhong id=\"1\">", "<ModifiedPhong id=\"1\" normalized=\"true\">",
                            "<OriginalBlinnPhong id=\"1\">", "<ModifiedBlinnPhong id=\"1\">",
                            "<ModifiedBlinnPhong id=\"1\" normalized=\"true\">", "<TorranceSparrow id=\"1\">",
                            "<TorranceSparrow id=\"1\" kdfresnel=\"true\">"};
    const std::vector<expectation> expect = expectations();
    for (size_t i = 0; i < expect.size(); ++i) {
        CAPTURE(expect[i].name);
        const std::string open = models[i];
        const std::string tag = open.substr(1, open.find(' ') - 1);
        const double lx = 2 * std::sin(deg(60)), lz = 2 * std::cos(deg(60));
        const double cx = -5 * std::sin(deg(30)), cz = 5 * std::cos(deg(30));
        char geometry[400];
        std::snprintf(geometry, sizeof geometry,
                      "<Lights><PointLight id=\"1\"><Position>%.17g 0 %.17g</Position><Intensity>1000 1000 1000</Intensity></PointLight></Lights>"
                      "<Cameras><Camera id=\"1\"><Position>%.17g 0 %.17g</Position><Gaze>%.17g 0 %.17g</Gaze><Up>0 1 0</Up>",
                      lx, lz, cx, cz, -cx, -cz);
        const std::string xml =
            std::string("<Scene><MaxRecursionDepth>0</MaxRecursionDepth>") + geometry +
            "<NearPlane>-0.01 0.01 -0.01 0.01</NearPlane><NearDistance>1</NearDistance>"
            "<ImageResolution>1 1</ImageResolution><ImageName>x.exr</ImageName></Camera></Cameras>"
            "<BRDFs>" + open + "<Exponent>10</Exponent></" + tag + "></BRDFs>"
            "<Materials><Material id=\"1\" BRDF=\"1\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance>"
            "<SpecularReflectance>0.25 0.25 0.25</SpecularReflectance><PhongExponent>99</PhongExponent>"
            "<RefractionIndex>1.5</RefractionIndex></Material></Materials>"
            "<VertexData>-10 -10 0 10 -10 0 10 10 0 -10 10 0</VertexData>"
            "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1 2 3 1 3 4</Faces></Mesh></Objects></Scene>";
        test::scratch_dir dir("course_brdf");
        const whitted_scene scene = load_xml_scene(dir.write("brdf.xml", xml));
        CHECK(scene.warnings.empty());
        const whitted_render r = render_whitted(scene, 0);
        // The shadow ray's offset moves the point by 1e-3 at most: d^2 and the angles change by
        // about 1e-3 relative.
        CHECK(r.img.pixel(0, 0).x() == doctest::Approx(250 * expect[i].value).epsilon(2e-3));
    }
}

TEST_CASE("course BRDFs: one line for a BRDF that is not there or malformed") {
    test::scratch_dir dir("course_brdf_bad");
    auto error_of = [&](const std::string& brdfs, const std::string& material_attr) -> std::string {
        const std::string xml =
            "<Scene><Cameras><Camera id=\"1\"><Position>0 0 5</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>"
            "<NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance><ImageResolution>4 4</ImageResolution>"
            "<ImageName>x.png</ImageName></Camera></Cameras><BRDFs>" + brdfs + "</BRDFs>"
            "<Materials><Material id=\"1\" " + material_attr + "><DiffuseReflectance>1 1 1</DiffuseReflectance></Material></Materials>"
            "<VertexData>0 0 0</VertexData><Objects><Sphere id=\"1\"><Material>1</Material><Center>1</Center><Radius>1</Radius></Sphere></Objects></Scene>";
        try {
            load_xml_scene(dir.write("bad.xml", xml));
        } catch (const scene_error& e) {
            return e.what();
        }
        return "";
    };
    const std::string ok = "<ModifiedPhong id=\"2\"><Exponent>5</Exponent></ModifiedPhong>";
    CHECK(error_of(ok, "BRDF=\"2\"").empty());
    CHECK(error_of(ok, "BRDF=\"3\"").find("BRDF=\"3\" names no entry of <BRDFs>") != std::string::npos);
    CHECK(error_of("<ModifiedPhong id=\"2\"></ModifiedPhong>", "").find("Exponent") != std::string::npos);
    CHECK(error_of("<ModifiedPhong id=\"2\" normalized=\"yes\"><Exponent>5</Exponent></ModifiedPhong>", "")
              .find("normalized=\"yes\" must be true or false") != std::string::npos);
    CHECK(error_of(ok + ok, "").find("defined twice") != std::string::npos);
    CHECK(error_of("<ModifiedPhong id=\"2\"><Exponent>-1</Exponent></ModifiedPhong>", "").find("Exponent") !=
          std::string::npos);
}

} // namespace test_course_brdf

namespace test_course_brdf {

TEST_CASE("course materials: colours may be written with commas, \"0.5, 0.5, 0.5\"") {
    test::scratch_dir dir("course_commas");
    auto scene = [&](const std::string& kd) {
        return "<Scene><Cameras><Camera id=\"1\"><Position>0 0 5</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>"
               "<NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance><ImageResolution>2 2</ImageResolution>"
               "<ImageName>x.exr</ImageName></Camera></Cameras><Materials><Material id=\"1\"><DiffuseReflectance>" +
               kd + "</DiffuseReflectance></Material></Materials><VertexData>0 0 0</VertexData><Objects><Sphere id=\"1\">"
               "<Material>1</Material><Center>1</Center><Radius>1</Radius></Sphere></Objects></Scene>";
    };
    CHECK_NOTHROW(load_xml_scene(dir.write("commas.xml", scene("0.5, 0.25,0.125"))));
    // A decimal comma is two numbers: refused, not misread.
    CHECK_THROWS_WITH_AS(load_xml_scene(dir.write("decimal.xml", scene("0,5 0,5 0,5"))),
                         doctest::Contains("has 6 numbers"), scene_error);
}

TEST_CASE("course materials: degamma=\"true\" reads each reflectance c as c^2.2") {
    // A sphere of kd 0.5 seen and lit head on from 4 units away by a point light of intensity
    // 1600: E = 100, the pixel 100 kd; with degamma 100 x 0.5^2.2 = 21.764.
    test::scratch_dir dir("course_degamma");
    for (bool degamma : {false, true}) {
        CAPTURE(degamma);
        const std::string xml =
            std::string("<Scene><Cameras><Camera id=\"1\"><Position>0 0 5</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>"
                        "<NearPlane>-0.001 0.001 -0.001 0.001</NearPlane><NearDistance>1</NearDistance>"
                        "<ImageResolution>1 1</ImageResolution><ImageName>x.exr</ImageName></Camera></Cameras>"
                        "<Lights><PointLight id=\"1\"><Position>0 0 5</Position><Intensity>1600 1600 1600</Intensity></PointLight></Lights>"
                        "<Materials><Material id=\"1\"") +
            (degamma ? " degamma=\"true\"" : "") +
            "><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance></Material></Materials>"
            "<VertexData>0 0 0</VertexData><Objects><Sphere id=\"1\"><Material>1</Material><Center>1</Center>"
            "<Radius>1</Radius></Sphere></Objects></Scene>";
        const whitted_scene s = load_xml_scene(dir.write("degamma.xml", xml));
        CHECK(s.warnings.empty());
        const double expected = degamma ? 100 * std::pow(0.5, 2.2) : 50;
        CHECK(render_whitted(s, 0).img.pixel(0, 0).x() == doctest::Approx(expected).epsilon(1e-3));
    }
}

} // namespace test_course_brdf
