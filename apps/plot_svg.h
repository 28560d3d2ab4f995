#pragma once
// A log-log line chart written as SVG text, for `bench --error` (image error against seconds).
// Hand-written because Debian packages no plotting library for C++; it does only what that chart
// needs: base-10 axes padded to half decades, decade grid and labels, minor ticks at 2..9, one
// polyline and marker shape per series, a legend, axis labels and a title. Every number is
// written with "%.2f", so the same data always gives the same bytes.

#include <rtweekend/core/scene_error.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace app {

struct plot_series {
    std::string name;         // legend text
    std::vector<double> x, y; // same length; only points with finite x > 0 and y > 0 are drawn
    std::string colour = "";  // "" = pick from a built-in palette by index
    bool points_only = false; // markers without a line (for single measurements)
};

struct plot_options {
    std::string title, x_label, y_label;
    int width = 720, height = 480;
};

// Where things go, in SVG pixels (y grows downwards). Public so tests can check the mapping.
struct plot_layout {
    double left = 0, top = 0, right = 0, bottom = 0;        // the plot area
    double log_x0 = 0, log_x1 = 1, log_y0 = 0, log_y1 = 1; // axis ranges as log10 of the data
    enum class place { inside, right, below };
    place legend = place::inside;                           // inside: in a corner of the plot area
    double legend_x = 0, legend_y = 0, legend_w = 0, legend_h = 0; // the legend's box
    int legend_columns = 1;                                 // entries go left to right, then down
    double legend_column_w = 0;

    double map_x(double x) const { return x_at(std::log10(x)); }
    double map_y(double y) const { return y_at(std::log10(y)); }
    double x_at(double log_x) const { return left + (log_x - log_x0) / (log_x1 - log_x0) * (right - left); }
    double y_at(double log_y) const { return bottom - (log_y - log_y0) / (log_y1 - log_y0) * (bottom - top); }
};

namespace plot_detail {

constexpr double tick_font = 12, label_font = 14, title_font = 16;
constexpr double legend_row = 20, legend_pad = 8, legend_swatch = 28;

inline bool drawable(double x, double y) { return std::isfinite(x) && std::isfinite(y) && x > 0 && y > 0; }

inline std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", v);
    return buf;
}

inline std::string escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        default: out += c;
        }
    }
    return out;
}

// No font metrics without a font library: 0.62 em per character (UTF-8 code point) is a little
// wider than Helvetica/DejaVu Sans on average, so boxes sized with it are not too narrow.
inline double text_width(const std::string& s, double font) {
    size_t code_points = 0;
    for (unsigned char c : s) code_points += (c & 0xC0) != 0x80;
    return 0.62 * font * double(code_points);
}

// The preferred size, or smaller (down to 9 px) if the text would not fit in `room` pixels.
inline double fit_font(const std::string& s, double preferred, double room) {
    const double width = text_width(s, preferred);
    return width <= room ? preferred : std::max(9.0, preferred * room / width);
}

// m x 10^e as "0.02", "1", "500" while that stays short, else "2e-5", "1e6".
inline std::string tick_label(int m, int e) {
    char buf[32];
    if (e >= 0 && e <= 4) std::snprintf(buf, sizeof buf, "%.0f", m * std::pow(10.0, e));
    else if (e < 0 && e >= -3) std::snprintf(buf, sizeof buf, "%.*f", -e, m * std::pow(10.0, e));
    else std::snprintf(buf, sizeof buf, "%de%d", m, e);
    return buf;
}

// Okabe-Ito colours: distinguishable with the common colour-vision deficiencies (their yellow,
// unreadable on white, is left out).
inline std::string colour_of(const plot_series& s, size_t index) {
    static const char* palette[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000"};
    return s.colour.empty() ? palette[index % 7] : s.colour;
}

// Shapes as well as colours tell the series apart: circle, square, diamond, triangle.
inline std::string marker(size_t index, double x, double y, const std::string& colour) {
    const std::string fill = " fill=\"" + escape(colour) + "\"/>\n";
    switch (index % 4) {
    case 0: return "<circle cx=\"" + num(x) + "\" cy=\"" + num(y) + "\" r=\"3.50\"" + fill;
    case 1: return "<rect x=\"" + num(x - 3.2) + "\" y=\"" + num(y - 3.2) + "\" width=\"6.40\" height=\"6.40\"" + fill;
    case 2:
        return "<path d=\"M" + num(x) + " " + num(y - 4.5) + "L" + num(x + 4.5) + " " + num(y) + "L" + num(x) + " " +
               num(y + 4.5) + "L" + num(x - 4.5) + " " + num(y) + "Z\"" + fill;
    default:
        return "<path d=\"M" + num(x) + " " + num(y - 4.5) + "L" + num(x + 4.2) + " " + num(y + 3) + "L" + num(x - 4.2) +
               " " + num(y + 3) + "Z\"" + fill;
    }
}

// [lo, hi] in log10 covering [min, max] with a little room, snapped to half decades, at least
// one decade wide (so at least one decade tick is always inside).
inline void axis_range(double min, double max, double& lo, double& hi) {
    lo = std::floor((min - 0.05) * 2) / 2;
    hi = std::ceil((max + 0.05) * 2) / 2;
    while (hi - lo < 1) { // widen on the side with less room
        if (min - lo < hi - max) lo -= 0.5;
        else hi += 0.5;
    }
}

} // namespace plot_detail

inline plot_layout loglog_layout(const std::vector<plot_series>& series, const plot_options& options) {
    using namespace plot_detail;
    double min_x = HUGE_VAL, max_x = -HUGE_VAL, min_y = HUGE_VAL, max_y = -HUGE_VAL;
    double name_width = 0;
    for (const auto& s : series) {
        if (s.x.size() != s.y.size())
            throw rt::scene_error("plot: series \"" + s.name + "\" has " + std::to_string(s.x.size()) + " x values but " +
                                  std::to_string(s.y.size()) + " y values");
        for (size_t i = 0; i < s.x.size(); ++i) {
            if (!drawable(s.x[i], s.y[i])) continue;
            min_x = std::min(min_x, std::log10(s.x[i])), max_x = std::max(max_x, std::log10(s.x[i]));
            min_y = std::min(min_y, std::log10(s.y[i])), max_y = std::max(max_y, std::log10(s.y[i]));
        }
        name_width = std::max(name_width, text_width(s.name, tick_font));
    }
    if (min_x > max_x) throw rt::scene_error("plot: no series has a point with x > 0 and y > 0");

    plot_layout l;
    axis_range(min_x, max_x, l.log_x0, l.log_x1);
    axis_range(min_y, max_y, l.log_y0, l.log_y1);
    // Margins: left for y tick labels and the rotated y label, bottom for x tick labels and the
    // x label, top for the title.
    l.left = 76, l.right = options.width - 20.0;
    l.top = options.title.empty() ? 16 : 40, l.bottom = options.height - 52.0;
    l.legend_column_w = legend_swatch + 8 + name_width + 16;
    auto legend_columns = [&](int columns) {
        const int rows = (int(series.size()) + columns - 1) / columns;
        l.legend_columns = columns;
        l.legend_w = 2 * legend_pad + l.legend_column_w * columns - 16;
        l.legend_h = 2 * legend_pad + legend_row * rows - 4;
    };
    legend_columns(1);

    // The legend goes in the first corner of the plot area that no marker or line crosses
    // (error-against-time curves fall to the right, so the upper right is usually free); if none
    // is free, in a column right of the plot area, which shrinks to make room; if that would
    // leave the plot narrower than half the chart, in rows below it.
    auto covers_data = [&](double bx, double by) {
        auto hit = [&](double px, double py) {
            return px > bx - 6 && px < bx + l.legend_w + 6 && py > by - 6 && py < by + l.legend_h + 6;
        };
        for (const auto& s : series) {
            bool have_previous = false;
            double qx = 0, qy = 0;
            for (size_t i = 0; i < s.x.size(); ++i) {
                if (!drawable(s.x[i], s.y[i])) { have_previous = false; continue; }
                double px = l.map_x(s.x[i]), py = l.map_y(s.y[i]);
                if (hit(px, py)) return true;
                // Lines: test points every few pixels along the segment.
                if (have_previous && !s.points_only)
                    for (int k = 1; k < 64; ++k)
                        if (hit(qx + (px - qx) * k / 64, qy + (py - qy) * k / 64)) return true;
                have_previous = true, qx = px, qy = py;
            }
        }
        return false;
    };
    const double inset = 10;
    const double corners[4][2] = {{l.right - inset - l.legend_w, l.top + inset},
                                  {l.left + inset, l.bottom - inset - l.legend_h},
                                  {l.left + inset, l.top + inset},
                                  {l.right - inset - l.legend_w, l.bottom - inset - l.legend_h}};
    bool placed = false;
    if (l.legend_w + 2 * inset < l.right - l.left && l.legend_h + 2 * inset < l.bottom - l.top)
        for (const auto& c : corners)
            if (!covers_data(c[0], c[1])) {
                l.legend = plot_layout::place::inside, l.legend_x = c[0], l.legend_y = c[1], placed = true;
                break;
            }
    if (!placed && options.width - 16 - l.legend_w - 12 - l.left >= 0.5 * options.width) {
        l.legend = plot_layout::place::right, l.right = options.width - 16 - l.legend_w - 12;
        l.legend_x = l.right + 12, l.legend_y = l.top;
    } else if (!placed) {
        legend_columns(std::max(1, int((l.right - l.left + 16 - 2 * legend_pad) / l.legend_column_w)));
        l.legend = plot_layout::place::below, l.bottom -= l.legend_h + 12;
        l.legend_x = l.left, l.legend_y = options.height - 8 - l.legend_h;
    }
    if (l.right - l.left < 100 || l.bottom - l.top < 100)
        throw rt::scene_error("plot: " + std::to_string(options.width) + "x" + std::to_string(options.height) +
                              " is too small for the chart and its legend");
    return l;
}

inline std::string render_loglog_svg(const std::vector<plot_series>& series, const plot_options& options) {
    using namespace plot_detail;
    const plot_layout l = loglog_layout(series, options);
    std::string svg;
    auto line = [&](double x1, double y1, double x2, double y2) {
        svg += "<line x1=\"" + num(x1) + "\" y1=\"" + num(y1) + "\" x2=\"" + num(x2) + "\" y2=\"" + num(y2) + "\"/>\n";
    };
    auto text = [&](double x, double y, const std::string& anchor, const std::string& s, const std::string& extra = "") {
        svg += "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\" text-anchor=\"" + anchor + "\"" + extra + ">" +
               escape(s) + "</text>\n";
    };

    svg += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(options.width) + "\" height=\"" +
           std::to_string(options.height) + "\" viewBox=\"0 0 " + std::to_string(options.width) + " " +
           std::to_string(options.height) + "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" fill=\"#222222\">\n";
    svg += "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";

    // Tick positions (log10 values) per axis. Decade labels are thinned when decades are closer
    // than a label's size; a short axis (at most 1.5 decades, so one or two decade labels) also
    // labels 2 and 5 if there is room, so that it has a readable scale.
    struct tick { double at; bool major; std::string label; };
    auto ticks = [](double lo, double hi, double pixels, double label_size) {
        std::vector<tick> t;
        const double per_decade = pixels / (hi - lo);
        const int stride = std::max(1, int(std::ceil(label_size / per_decade)));
        const bool minor_labels = hi - lo <= 1.5 && 0.3 * per_decade >= label_size;
        for (int d = int(std::floor(lo)); d <= int(std::ceil(hi)); ++d)
            for (int m = 1; m <= 9; ++m) {
                double at = d + std::log10(double(m));
                if (at < lo - 1e-9 || at > hi + 1e-9) continue;
                bool label = m == 1 ? ((d % stride) + stride) % stride == 0 : minor_labels && (m == 2 || m == 5);
                t.push_back({at, m == 1, label ? tick_label(m, d) : ""});
            }
        return t;
    };
    const auto x_ticks = ticks(l.log_x0, l.log_x1, l.right - l.left, 56);
    const auto y_ticks = ticks(l.log_y0, l.log_y1, l.bottom - l.top, 26);

    // Grid: minor lines barely visible, decades light grey; drawn first so data lies on top.
    for (int major = 0; major < 2; ++major) {
        svg += std::string("<g stroke=\"") + (major ? "#d0d0d0" : "#efefef") + "\" stroke-width=\"1\">\n";
        for (const auto& t : x_ticks)
            if (t.major == bool(major)) line(l.x_at(t.at), l.top, l.x_at(t.at), l.bottom);
        for (const auto& t : y_ticks)
            if (t.major == bool(major)) line(l.left, l.y_at(t.at), l.right, l.y_at(t.at));
        svg += "</g>\n";
    }

    // Series: lines broken wherever a point cannot be drawn, then markers over them.
    for (size_t i = 0; i < series.size(); ++i) {
        const auto& s = series[i];
        const std::string colour = escape(colour_of(s, i));
        svg += "<g>\n";
        std::string points;
        int run = 0;
        auto flush = [&] {
            if (run >= 2 && !s.points_only)
                svg += "<polyline points=\"" + points + "\" fill=\"none\" stroke=\"" + colour +
                       "\" stroke-width=\"2\" stroke-linejoin=\"round\"/>\n";
            points.clear(), run = 0;
        };
        for (size_t k = 0; k < s.x.size(); ++k) {
            if (!drawable(s.x[k], s.y[k])) { flush(); continue; }
            points += (run++ ? " " : "") + num(l.map_x(s.x[k])) + "," + num(l.map_y(s.y[k]));
        }
        flush();
        for (size_t k = 0; k < s.x.size(); ++k)
            if (drawable(s.x[k], s.y[k])) svg += marker(i, l.map_x(s.x[k]), l.map_y(s.y[k]), colour_of(s, i));
        svg += "</g>\n";
    }

    // Axes: a dark frame, outward ticks (5 px at decades, 3 px between) and their labels.
    svg += "<rect x=\"" + num(l.left) + "\" y=\"" + num(l.top) + "\" width=\"" + num(l.right - l.left) +
           "\" height=\"" + num(l.bottom - l.top) + "\" fill=\"none\" stroke=\"#333333\" stroke-width=\"1\"/>\n";
    svg += "<g stroke=\"#333333\" stroke-width=\"1\">\n";
    for (const auto& t : x_ticks) line(l.x_at(t.at), l.bottom, l.x_at(t.at), l.bottom + (t.major ? 5 : 3));
    for (const auto& t : y_ticks) line(l.left, l.y_at(t.at), l.left - (t.major ? 5 : 3), l.y_at(t.at));
    svg += "</g>\n<g font-size=\"" + num(tick_font) + "\">\n";
    for (const auto& t : x_ticks)
        if (!t.label.empty()) text(l.x_at(t.at), l.bottom + 20, "middle", t.label);
    for (const auto& t : y_ticks)
        if (!t.label.empty()) text(l.left - 8, l.y_at(t.at) + 4, "end", t.label);
    svg += "</g>\n";

    const double mid_x = (l.left + l.right) / 2, mid_y = (l.top + l.bottom) / 2;
    auto size = [&](const std::string& s, double preferred, double room) {
        return " font-size=\"" + num(fit_font(s, preferred, room)) + "\"";
    };
    if (!options.x_label.empty())
        text(mid_x, l.bottom + 40, "middle", options.x_label, size(options.x_label, label_font, l.right - l.left));
    if (!options.y_label.empty())
        text(20, mid_y, "middle", options.y_label,
             size(options.y_label, label_font, l.bottom - l.top) + " transform=\"rotate(-90 20.00 " + num(mid_y) + ")\"");
    if (!options.title.empty()) // centred on the chart, not the plot area: long titles fit better
        text(options.width / 2.0, 26, "middle", options.title,
             size(options.title, title_font, options.width - 20.0) + " font-weight=\"bold\"");

    // Legend: a white box (opaque, in case it sits over grid lines), one row per series.
    svg += "<g font-size=\"" + num(tick_font) + "\">\n";
    svg += "<rect x=\"" + num(l.legend_x) + "\" y=\"" + num(l.legend_y) + "\" width=\"" + num(l.legend_w) +
           "\" height=\"" + num(l.legend_h) + "\" fill=\"#ffffff\" stroke=\"#bbbbbb\" stroke-width=\"1\"/>\n";
    for (size_t i = 0; i < series.size(); ++i) {
        const double row_y = l.legend_y + legend_pad + legend_row * double(int(i) / l.legend_columns) + 8;
        const double sx = l.legend_x + legend_pad + l.legend_column_w * double(int(i) % l.legend_columns);
        const std::string colour = colour_of(series[i], i);
        if (!series[i].points_only)
            svg += "<line x1=\"" + num(sx) + "\" y1=\"" + num(row_y) + "\" x2=\"" + num(sx + legend_swatch) + "\" y2=\"" +
                   num(row_y) + "\" stroke=\"" + escape(colour) + "\" stroke-width=\"2\"/>\n";
        svg += marker(i, sx + legend_swatch / 2, row_y, colour);
        text(sx + legend_swatch + 8, row_y + 4, "start", series[i].name);
    }
    svg += "</g>\n</svg>\n";
    return svg;
}

} // namespace app
