#pragma once
// tonemap: the global photographic tone reproduction operator of Reinhard, Stark, Shirley and
// Ferwerda, "Photographic Tone Reproduction for Digital Images" (SIGGRAPH 2002, eqs. 1-4), exactly as
// CENG795's homework 5 and its reference images use it (shared/formats/ceng795-later.md, section 9):
//
//   Y     = 0.2126 R + 0.7152 G + 0.0722 B                        per pixel
//   Ybar  = exp(mean over all pixels of ln(1e-6 + Y))             black pixels included
//   L     = key Y / Ybar
//   burn > 0:  Lwhite = L of the pixel at the (100 - burn)th percentile, Ld = L (1 + L / Lwhite^2) / (1 + L)
//   burn = 0:  Ld = L / (1 + L)
//   C_out = Ld (C / Y)^saturation      for C in R, G, B (0 where Y = 0)
//   byte  = floor(255 clamp(C_out, 0, 1)^(1 / gamma))             truncated, as the references are
//
// The percentile: the pixels' L sorted ascending, the one at index floor(N (100 - burn) / 100)
// (the last for burn = 0+); that pixel, and all brighter, map to white. The course does not say
// which percentile convention; this one is the usual implementation's.
//
//   std::vector<unsigned char> rgb = tonemap_photographic(img, {0.18, 1, 1, 2.2});

#include "../core/engine_linkage.h"
#include "image.h"

#include <vector>

namespace rt {

struct photographic_tonemap {
    double key = 0.18;       // the middle grey the log-average luminance maps to
    double burn = 0;         // percent of pixels burnt out to white, in [0, 100)
    double saturation = 1;   // 0: grey; 1: the image's own colours
    double gamma = 2.2;      // the display's: the output is clamp(C)^(1/gamma)
};

// The 8-bit RGB bytes of `img` (rows top to bottom), tone mapped as above. Throws scene_error for
// a key, gamma or saturation that is not positive (saturation: not negative) and finite, or a burn
// outside [0, 100). NaN and negative channel values count as 0.
RTWEEKEND_ENGINE_FUNCTION std::vector<unsigned char> tonemap_photographic(const image& img,
                                                                          const photographic_tonemap& t);

// --- IMPLEMENTATION -----------------------------------------------------------------------------
#if RTWEEKEND_ENGINE_BODIES

} // namespace rt

#include "../core/scene_error.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace rt {

RTWEEKEND_ENGINE_FUNCTION std::vector<unsigned char> tonemap_photographic(const image& img,
                                                                          const photographic_tonemap& t) {
    auto positive = [](double x) { return std::isfinite(x) && x > 0; };
    if (!positive(t.key)) throw scene_error("tone mapping: the key must be positive, got " + number_text(t.key));
    if (!positive(t.gamma)) throw scene_error("tone mapping: gamma must be positive, got " + number_text(t.gamma));
    if (!(std::isfinite(t.saturation) && t.saturation >= 0))
        throw scene_error("tone mapping: saturation must be 0 or more, got " + number_text(t.saturation));
    if (!(t.burn >= 0 && t.burn < 100))
        throw scene_error("tone mapping: burn must be a percentage in [0, 100), got " + number_text(t.burn));
    const std::vector<float>& data = img.data();
    const size_t pixels = data.size() / 3;
    std::vector<unsigned char> out(data.size(), 0);
    if (pixels == 0) return out;
    auto channel = [&](size_t i) {
        const double c = data[i];
        return c > 0 && std::isfinite(c) ? c : 0.0; // NaN, negative, infinite: 0
    };
    std::vector<double> Y(pixels);
    double log_sum = 0;
    for (size_t p = 0; p < pixels; ++p) {
        Y[p] = 0.2126 * channel(3 * p) + 0.7152 * channel(3 * p + 1) + 0.0722 * channel(3 * p + 2);
        log_sum += std::log(1e-6 + Y[p]);
    }
    const double y_bar = std::exp(log_sum / double(pixels));
    const double scale = t.key / y_bar;
    double white2 = 0;
    if (t.burn > 0) {
        std::vector<double> L(pixels);
        for (size_t p = 0; p < pixels; ++p) L[p] = scale * Y[p];
        const size_t at = std::min(pixels - 1, size_t(double(pixels) * (100 - t.burn) / 100));
        std::nth_element(L.begin(), L.begin() + ptrdiff_t(at), L.end());
        white2 = L[at] * L[at];
    }
    for (size_t p = 0; p < pixels; ++p) {
        if (!(Y[p] > 0)) continue; // black stays black
        const double L = scale * Y[p];
        const double Ld = white2 > 0 ? L * (1 + L / white2) / (1 + L) : L / (1 + L);
        for (size_t k = 0; k < 3; ++k) {
            const double c = Ld * std::pow(channel(3 * p + k) / Y[p], t.saturation);
            const double v = 255 * std::pow(std::min(1.0, std::max(0.0, c)), 1 / t.gamma);
            out[3 * p + k] = static_cast<unsigned char>(std::min(255.0, std::floor(v)));
        }
    }
    return out;
}

#endif // RTWEEKEND_ENGINE_BODIES

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::photographic_tonemap;
using rt::tonemap_photographic;
#endif
