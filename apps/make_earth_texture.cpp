// make_earth_texture: writes an invented, earth-like planet map for book 2's globe (the book's
// earthmap.jpg is not ours to ship), as an equirectangular PNG: u = longitude, v = latitude,
// row 0 the north pole.
//
//   make_earth_texture OUT.png [--width W]      (default 1024; the height is W / 2)
//
// The terrain is fractal Perlin noise (rtweekend/perlin.h) sampled on the unit sphere, not on the
// flat map, so it has no seam at the date line and no pinching at the poles. Where the elevation
// is above sea level it is land, green in the lowlands and brown to grey higher up, drier (more
// tan) near the tropics; below it, ocean, darker where deeper; beyond about 70 degrees of latitude
// (with a noisy edge), ice. The noise tables come from a fixed pcg32 seed, so the file is the same
// on every machine and every run. tests/data/textures/earthmap.png was made with it (see
// tests/data/README.md).

#include <rtweekend/core/rng.h>
#include <rtweekend/core/file.h>
#include <rtweekend/image/image_write.h>
#include <rtweekend/perlin.h>
#include <rtweekend/core/scene_error.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

namespace {

struct rgb {
    double r, g, b;
};

// Shading in a few flat bands, like a printed atlas: they keep the PNG small (under 400 KB).
double banded(double t, double bands) { return std::floor(std::clamp(t, 0.0, 1.0) * bands) / bands; }

rgb mix(const rgb& a, const rgb& b, double t) {
    t = std::clamp(t, 0.0, 1.0);
    return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t};
}

// Signed fractal sum: each octave twice the frequency and half the weight of the last.
double fbm(const rt::perlin& noise, const rt::point3& p, int octaves) {
    double sum = 0, weight = 1;
    rt::point3 q = p;
    for (int i = 0; i < octaves; ++i) {
        sum += weight * noise.noise(q);
        weight *= 0.5;
        q *= 2.03; // not exactly 2, so the octaves' lattices do not line up
    }
    return sum;
}

// The colour of the planet in the direction d (a unit vector; y towards the north pole).
rgb surface_colour(const rt::perlin& terrain, const rt::perlin& climate, const rt::point3& d) {
    const double latitude = std::asin(std::clamp(d.y(), -1.0, 1.0)) * 180 / rt::pi; // degrees
    const double elevation = fbm(terrain, 1.6 * d + rt::vec3(11.3, -4.7, 2.9), 8);
    const double dryness = 0.5 + 0.8 * fbm(climate, 2.5 * d, 4) - 0.012 * std::fabs(std::fabs(latitude) - 25);
    const double ice_edge = 70 + 8 * fbm(climate, 4.0 * d + rt::vec3(3, 3, 3), 3);

    const double sea_level = 0.04;
    rgb c;
    if (elevation < sea_level) {
        // Depth shading from the coarse octaves only: open ocean is smooth (and compresses well).
        const double depth = (sea_level - fbm(terrain, 1.6 * d + rt::vec3(11.3, -4.7, 2.9), 3)) / 0.5;
        c = mix({0.16, 0.38, 0.62}, {0.03, 0.09, 0.30}, banded(depth, 8)); // shallow to deep water
    } else {
        // Height shading from fewer octaves than the coastline: smoother land, a smaller file.
        const double height = (fbm(terrain, 1.6 * d + rt::vec3(11.3, -4.7, 2.9), 5) - sea_level) / 0.45;
        const rgb lowland = mix({0.22, 0.42, 0.16}, {0.72, 0.62, 0.40}, banded(dryness, 6));
        c = mix(lowland, {0.45, 0.36, 0.26}, banded(height * 1.4, 6));             // hills: brown
        c = mix(c, {0.55, 0.53, 0.50}, banded((height - 0.7) * 3, 4));              // mountains: grey rock
    }
    if (std::fabs(latitude) > ice_edge) c = mix(c, {0.93, 0.95, 0.97}, (std::fabs(latitude) - ice_edge) / 3);
    return c;
}

unsigned char to_byte(double x) { return static_cast<unsigned char>(std::lround(255 * std::clamp(x, 0.0, 1.0))); }

void append_bytes(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

} // namespace

int main(int argc, char** argv) {
    std::string out;
    int width = 1024;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--width") == 0 && i + 1 < argc) {
            width = std::atoi(argv[++i]);
        } else if (argv[i][0] != '-' && out.empty()) {
            out = argv[i];
        } else {
            std::fprintf(stderr, "usage: make_earth_texture OUT.png [--width W]\n");
            return 2;
        }
    }
    if (out.empty() || width < 2 || width > 16384 || width % 2 != 0) {
        std::fprintf(stderr, "usage: make_earth_texture OUT.png [--width W]   (W even, 2..16384)\n");
        return 2;
    }
    const int height = width / 2;

    // The noise tables draw from random_double(); these fixed generators make them the same
    // everywhere (rand() would differ between C libraries).
    rt::pcg32 terrain_rng(20240521), climate_rng(7);
    auto make_noise = [](rt::pcg32& g) {
        rt::detail::scoped_sample_rng guard(g);
        return rt::perlin();
    };
    const rt::perlin terrain = make_noise(terrain_rng), climate = make_noise(climate_rng);

    std::vector<unsigned char> bytes(size_t(width) * size_t(height) * 3);
    for (int j = 0; j < height; ++j) {
        // The pixel centre's latitude, north at the top; longitude as sphere.h's u: phi = 2 pi u
        // measured from -x, turning from -x towards -z.
        const double theta = rt::pi * (1 - (j + 0.5) / height); // from the south pole
        for (int i = 0; i < width; ++i) {
            const double phi = 2 * rt::pi * (i + 0.5) / width;
            const rt::point3 d(-std::cos(phi) * std::sin(theta), -std::cos(theta), std::sin(phi) * std::sin(theta));
            const rgb c = surface_colour(terrain, climate, d);
            unsigned char* px = &bytes[(size_t(j) * size_t(width) + size_t(i)) * 3];
            px[0] = to_byte(c.r); // the colours above are sRGB-encoded values, as a PNG holds
            px[1] = to_byte(c.g);
            px[2] = to_byte(c.b);
        }
    }
    std::string png;
    if (!stbi_write_png_to_func(append_bytes, &png, width, height, 3, bytes.data(), width * 3)) {
        std::fprintf(stderr, "make_earth_texture: error: PNG encoding failed\n");
        return 1;
    }
    try {
        rt::write_file_atomically(out, png);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "make_earth_texture: error: %s\n", e.what());
        return 1;
    }
    std::fprintf(stderr, "make_earth_texture: wrote %s (%dx%d, %zu bytes)\n", out.c_str(), width, height, png.size());
    return 0;
}
