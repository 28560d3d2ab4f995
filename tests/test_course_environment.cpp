// The course's environment light (homework 5's <SphericalDirectionalLight>; course/course_lights.h,
// course/whitted.h; shared/formats/ceng795-later.md section 6.4) and Radiance HDR images
// (image/image_read.h): texels at directions worked out from the lat-long formula, a floor under a
// constant sky (pi kd L by the integral of the cosine), reflected rays that leave the scene, the
// course's path tracer under the same sky, and one-line refusals.

#include <rtweekend/course/whitted.h>
#include <rtweekend/image/image_read.h>
#include <rtweekend/io/xml_scene.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace test_course_environment {

using namespace rt;

namespace {

constexpr double pi_d = 3.14159265358979323846;

// A flat (not run-length encoded) Radiance HDR file of w x h pixels, row 0 the top, whose pixel
// (x, y) is value(x, y) on all three channels: each written as mantissa m and exponent e with
// value = m 2^(e - 136) (stb_image's reading of RGBE), m = value / 2^k for a power k that keeps
// m below 256. Values must be m 2^k for a whole m below 256.
template <class F>
std::string hdr_file(int w, int h, F value) {
    std::string out = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(h) + " +X " + std::to_string(w) + "\n";
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double v = value(x, y);
            int e = 136;
            while (v >= 256) {
                v /= 2;
                ++e;
            }
            while (v < 128 && e > 1) {
                v *= 2;
                --e;
            }
            const auto m = static_cast<unsigned char>(v);
            out += std::string{char(m), char(m), char(m), char(e)};
        }
    return out;
}

// The mean of an image's red channel and its standard error, from the spread of its pixels.
std::pair<double, double> mean_and_error(const image& img) {
    const int n = img.width() * img.height();
    double s = 0, s2 = 0;
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) {
            const double v = img.pixel(x, y).x();
            s += v;
            s2 += v * v;
        }
    const double mean = s / n;
    return {mean, std::sqrt(std::fmax(0.0, (s2 - n * mean * mean) / (n - 1)) / n)};
}

// The texel values of the test's 4 x 2 map: 10 (x + 1) + 100 y.
double texel(int x, int y) { return 10.0 * (x + 1) + 100.0 * y; }

std::string scene_with(const std::string& camera, const std::string& rest, const std::string& image_file = "sky.hdr") {
    return "<Scene><MaxRecursionDepth>2</MaxRecursionDepth><BackgroundColor>1 2 3</BackgroundColor><Cameras>" + camera +
           "</Cameras><Textures><Images><Image id=\"1\">" + image_file +
           "</Image></Images></Textures><Lights><SphericalDirectionalLight id=\"1\"><ImageId>1</ImageId>"
           "</SphericalDirectionalLight></Lights>" + rest + "</Scene>";
}

std::string camera_xml(const std::string& position, const std::string& gaze, int size, int samples,
                       const std::string& extra = "") {
    return "<Camera id=\"1\"><Position>" + position + "</Position><Gaze>" + gaze +
           "</Gaze><Up>0 0 1</Up><NearPlane>-0.0001 0.0001 -0.0001 0.0001</NearPlane><NearDistance>1</NearDistance>"
           "<ImageResolution>" + std::to_string(size) + " " + std::to_string(size) +
           "</ImageResolution><ImageName>x.exr</ImageName><NumSamples>" + std::to_string(samples) + "</NumSamples>" +
           extra + "</Camera>";
}

} // namespace

TEST_CASE("course environment: a Radiance HDR file reads to the values written") {
    test::scratch_dir dir("course_env_hdr");
    const loaded_image img = read_image(dir.write("a.hdr", hdr_file(4, 2, texel)));
    CHECK(img.format == "HDR");
    CHECK_FALSE(img.display_encoded);
    REQUIRE(img.pixels.width() == 4);
    REQUIRE(img.pixels.height() == 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) CHECK(img.pixels.pixel(x, y).y() == float(texel(x, y)));
    // Cut short: one line.
    std::string cut = hdr_file(4, 2, texel);
    cut.resize(cut.size() - 6);
    try {
        read_image(dir.write("cut.hdr", cut));
        FAIL("a truncated HDR file was read");
    } catch (const scene_error& e) {
        CHECK(std::string(e.what()).find('\n') == std::string::npos);
        CHECK(std::string(e.what()).find("cut.hdr") != std::string::npos);
    }
}

TEST_CASE("course environment: camera rays that miss see the texel of their direction") {
    // u = (1 + atan2(d_x, -d_z) / pi) / 2, v = acos(d_y) / pi; texel (floor(4 u), floor(2 v)).
    struct probe {
        const char* gaze;
        int x, y;
    } probes[] = {
        {"1 0.5 0", 3, 0},    // u = 0.75, v = acos(0.447) / pi = 0.35
        {"-1 -0.5 0", 1, 1},  // u = 0.25, v = 0.65
        {"0.1 0.3 -1", 2, 0}, // u = (1 + atan2(0.1, 1) / pi) / 2 = 0.516, v = 0.41
        {"0.2 -0.4 1", 3, 1}, // u = (1 + atan2(0.2, -1) / pi) / 2 = 0.968, v = 0.63
    };
    test::scratch_dir dir("course_env_miss");
    dir.write("sky.hdr", hdr_file(4, 2, texel));
    for (const probe& p : probes) {
        CAPTURE(p.gaze);
        const whitted_scene s =
            load_xml_scene(dir.write("miss.xml", scene_with(camera_xml("0 0 0", p.gaze, 1, 1), "<VertexData>0 0 0</VertexData>")));
        CHECK(s.warnings.empty());
        CHECK(render_whitted(s, 0).img.pixel(0, 0).x() == float(texel(p.x, p.y)));
    }
}

TEST_CASE("course environment: a mirror shows the sky, and a floor under a constant sky is pi kd L") {
    test::scratch_dir dir("course_env_floor");
    dir.write("sky.hdr", hdr_file(4, 2, texel));
    dir.write("grey.hdr", hdr_file(4, 2, [](int, int) { return 100.0; }));
    const std::string floor = "<VertexData>-50 -50 0 50 -50 0 50 50 0 -50 50 0</VertexData>"
                              "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1 2 3 1 3 4</Faces></Mesh></Objects>";
    // A perfect mirror z = 0 (MirrorReflectance 1, nothing else) seen along (-1, -0.5, -1) reflects
    // the ray to (-1, -0.5, 1) / 1.5: u = (1 + atan2(-1, -1) / pi) / 2 = 0.125, v = acos(-1/3) / pi
    // = 0.61 (the map's +y is up): texel (0, 1).
    const std::string mirror = "<Materials><Material id=\"1\" type=\"mirror\"><MirrorReflectance>1 1 1</MirrorReflectance></Material></Materials>";
    const whitted_scene m = load_xml_scene(dir.write("mirror.xml", scene_with(camera_xml("1 0.5 1", "-1 -0.5 -1", 1, 1), mirror + floor)));
    CHECK(render_whitted(m, 0).img.pixel(0, 0).x() == doctest::Approx(texel(0, 1)).epsilon(1e-6));

    // kd 0.5 (the level-1 model: f cos = kd cos) under L = 100 everywhere: the mean of 2 pi L kd cos
    // over cos uniform in [0, 1) is pi kd L. 16 pixels of 1024 samples; five standard errors.
    const std::string plain = "<Materials><Material id=\"1\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance></Material></Materials>";
    const whitted_scene f = load_xml_scene(dir.write("floor.xml", scene_with(camera_xml("1 0 1", "-1 0 -1", 4, 1024), plain + floor, "grey.hdr")));
    const auto [mean, error] = mean_and_error(render_whitted(f, 0).img);
    const double expected = pi_d * 0.5 * 100;
    INFO(mean << " +- " << error << ", expected " << expected);
    CHECK(std::fabs(mean - expected) <= 5 * error + 1e-3 * expected);
    CHECK(error < 0.02 * expected);

    // The course's path tracer under the same sky, a floor of albedo 0.5 (normalised modified
    // Phong, ks 0), one bounce: 0.5 L = 50, whether the sky is sampled by next-event estimation
    // or found by the indirect ray (which then sees it), uniformly or by the cosine.
    const std::string brdf = "<BRDFs><ModifiedPhong id=\"1\" normalized=\"true\"><Exponent>1</Exponent></ModifiedPhong></BRDFs>"
                             "<Materials><Material id=\"1\" BRDF=\"1\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance></Material></Materials>";
    for (const char* params : {"", "NextEventEstimation", "ImportanceSampling", "NextEventEstimation ImportanceSampling"}) {
        CAPTURE(params);
        const std::string pt = std::string("<Renderer>PathTracing</Renderer><RendererParams>") + params + "</RendererParams>";
        const whitted_scene p = load_xml_scene(
            dir.write("pt.xml", scene_with(camera_xml("1 0 1", "-1 0 -1", 4, 1024, pt), brdf + floor, "grey.hdr")));
        const auto [pm, pe] = mean_and_error(render_whitted(p, 0).img);
        INFO(pm << " +- " << pe);
        CHECK(std::fabs(pm - 50) <= 5 * pe + 0.05);
    }
}

TEST_CASE("course environment: one line for what cannot be read") {
    test::scratch_dir dir("course_env_bad");
    dir.write("sky.hdr", hdr_file(4, 2, texel));
    auto error_of = [&](const std::string& xml) -> std::string {
        try {
            load_xml_scene(dir.write("bad.xml", xml));
        } catch (const scene_error& e) {
            return e.what();
        }
        return "";
    };
    const std::string cam = camera_xml("0 0 0", "1 0 0", 1, 1);
    const std::string rest = "<VertexData>0 0 0</VertexData>";
    CHECK(error_of(scene_with(cam, rest)).empty());
    CHECK(error_of(scene_with(cam, rest, "missing.hdr")).find("missing.hdr") != std::string::npos);
    std::string wrong_id = scene_with(cam, rest);
    wrong_id.replace(wrong_id.find("<ImageId>1"), 10, "<ImageId>7");
    CHECK(error_of(wrong_id).find("<ImageId> 7 names no <Image> of <Textures>") != std::string::npos);
    std::string probe = scene_with(cam, rest);
    probe.replace(probe.find("<SphericalDirectionalLight id=\"1\">"), 34, "<SphericalDirectionalLight id=\"1\" type=\"probe\">");
    CHECK(error_of(probe).find("type=\"probe\" is not supported (latlong is)") != std::string::npos);
    dir.write("negative.pfm", std::string("PF\n1 1\n-1\n") + std::string("\0\0\x80\xbf\0\0\x80\x3f\0\0\x80\x3f", 12));
    CHECK(error_of(scene_with(cam, rest, "negative.pfm")).find("negative or not a finite number") != std::string::npos);
}

} // namespace test_course_environment
