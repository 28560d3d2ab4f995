// The log-log SVG chart (apps/plot_svg.h): the SVG text is taken apart here with a few string
// helpers, and its coordinates are checked against positions worked out from the plot area and
// the axis ranges, not by calling the chart's own mapping.

#include "plot_svg.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace test_plot_svg {

using app::plot_layout;
using app::plot_options;
using app::plot_series;

namespace {

// Every opening tag `<name ...>` of one element name, as text.
std::vector<std::string> tags(const std::string& svg, const std::string& name) {
    std::vector<std::string> out;
    for (size_t at = svg.find("<" + name + " "); at != std::string::npos; at = svg.find("<" + name + " ", at + 1))
        out.push_back(svg.substr(at, svg.find('>', at) - at + 1));
    return out;
}

std::string attr(const std::string& tag, const std::string& name) {
    size_t at = tag.find(" " + name + "=\"");
    REQUIRE(at != std::string::npos);
    at += name.size() + 3;
    return tag.substr(at, tag.find('"', at) - at);
}

double num_attr(const std::string& tag, const std::string& name) { return std::atof(attr(tag, name).c_str()); }

struct text_element {
    double x, y;
    std::string content; // as written, entities not decoded
};

std::vector<text_element> texts(const std::string& svg) {
    std::vector<text_element> out;
    for (size_t at = svg.find("<text "); at != std::string::npos; at = svg.find("<text ", at + 1)) {
        size_t open_end = svg.find('>', at), close = svg.find("</text>", at);
        std::string tag = svg.substr(at, open_end - at + 1);
        out.push_back({num_attr(tag, "x"), num_attr(tag, "y"), svg.substr(open_end + 1, close - open_end - 1)});
    }
    return out;
}

std::vector<std::pair<double, double>> polyline_points(const std::string& tag) {
    std::vector<std::pair<double, double>> out;
    std::string points = attr(tag, "points");
    const char* p = points.c_str();
    while (*p) {
        char* end;
        double x = std::strtod(p, &end);
        REQUIRE(*end == ',');
        double y = std::strtod(end + 1, &end);
        out.push_back({x, y});
        p = end;
        while (*p == ' ') ++p;
    }
    return out;
}

// Well-formed XML, as far as this writer can go wrong: tags nest and close, attribute quotes
// pair up, and text has no raw '<' and no '&' outside the five predefined entities.
bool well_formed(const std::string& svg) {
    std::vector<std::string> open;
    size_t at = 0;
    auto entities_ok = [](const std::string& s) {
        for (size_t i = s.find('&'); i != std::string::npos; i = s.find('&', i + 1)) {
            bool ok = false;
            for (const char* e : {"&amp;", "&lt;", "&gt;", "&quot;", "&apos;"}) ok |= s.compare(i, std::strlen(e), e) == 0;
            if (!ok) return false;
        }
        return true;
    };
    while (at < svg.size()) {
        size_t lt = svg.find('<', at);
        if (!entities_ok(svg.substr(at, lt == std::string::npos ? std::string::npos : lt - at))) return false;
        if (lt == std::string::npos) break;
        if (svg.compare(lt, 2, "<?") == 0) {
            at = svg.find("?>", lt);
            if (at == std::string::npos || lt != 0) return false;
            at += 2;
            continue;
        }
        size_t gt = svg.find('>', lt);
        if (gt == std::string::npos) return false;
        std::string tag = svg.substr(lt + 1, gt - lt - 1);
        size_t quotes = 0;
        for (char c : tag) quotes += c == '"';
        if (quotes % 2 || tag.find('<') != std::string::npos || !entities_ok(tag)) return false;
        if (tag[0] == '/') {
            if (open.empty() || open.back() != tag.substr(1)) return false;
            open.pop_back();
        } else if (tag.back() != '/') {
            open.push_back(tag.substr(0, tag.find(' ')));
        }
        at = gt + 1;
    }
    return open.empty();
}

plot_series one_over_x() {
    plot_series s{"1/x", {}, {}};
    for (int i = 1; i <= 1000; ++i) s.x.push_back(i), s.y.push_back(1.0 / i);
    return s;
}

} // namespace

TEST_CASE("plot_svg: x = 1..1000, y = 1/x: half-decade padding, and decades map to equal pixel steps") {
    const plot_options options{"title", "x", "y"};
    const std::vector<plot_series> series{one_over_x()};
    const plot_layout l = app::loglog_layout(series, options);
    const std::string svg = app::render_loglog_svg(series, options);

    // Data from 10^0 to 10^3 (x) and 10^-3 to 10^0 (y), padded by half a decade each side.
    CHECK(l.log_x0 == -0.5);
    CHECK(l.log_x1 == 3.5);
    CHECK(l.log_y0 == -3.5);
    CHECK(l.log_y1 == 0.5);
    CHECK(0 < l.left);
    CHECK(l.left + 100 < l.right);
    CHECK(l.right <= options.width);
    CHECK(0 < l.top);
    CHECK(l.top + 100 < l.bottom);
    CHECK(l.bottom <= options.height);

    auto lines = tags(svg, "polyline");
    REQUIRE(lines.size() == 1);
    auto points = polyline_points(lines[0]);
    REQUIRE(points.size() == 1000);
    // 10^k is k + 0.5 of the 4 decades from the left; 10^-k is 3.5 - k from the bottom.
    const double decade_w = (l.right - l.left) / 4, decade_h = (l.bottom - l.top) / 4;
    const int at_decade[] = {0, 9, 99, 999}; // x = 1, 10, 100, 1000
    for (int k = 0; k < 4; ++k) {
        CAPTURE(k);
        CHECK(std::abs(points[at_decade[k]].first - (l.left + (k + 0.5) * decade_w)) <= 0.006);
        CHECK(std::abs(points[at_decade[k]].second - (l.bottom - (3.5 - k) * decade_h)) <= 0.006);
        if (k > 0) { // equal steps, to the 0.01 px the SVG is written with
            CHECK(std::abs(points[at_decade[k]].first - points[at_decade[k - 1]].first - decade_w) <= 0.011);
            CHECK(std::abs(points[at_decade[k]].second - points[at_decade[k - 1]].second - decade_h) <= 0.011);
        }
    }
    // x = 2: log10(2) of a decade right of x = 1.
    CHECK(std::abs(points[1].first - (l.left + (0.5 + std::log10(2.0)) * decade_w)) <= 0.006);
    for (size_t i = 1; i < points.size(); ++i) { // rightwards and downwards
        CHECK(points[i].first >= points[i - 1].first);
        CHECK(points[i].second >= points[i - 1].second);
    }
}

TEST_CASE("plot_svg: a tick label at every decade, under its grid line, none at the half-decade ends") {
    const plot_options options{"", "", ""};
    const std::vector<plot_series> series{one_over_x()};
    const plot_layout l = app::loglog_layout(series, options);
    std::set<std::string> x_labels, y_labels;
    for (const auto& t : texts(app::render_loglog_svg(series, options))) {
        if (t.x < l.left) y_labels.insert(t.content);
        if (t.y > l.bottom) x_labels.insert(t.content);
        if (t.content == "100" && t.y > l.bottom) CHECK(std::abs(t.x - (l.left + 2.5 * (l.right - l.left) / 4)) <= 0.006);
        if (t.content == "0.01" && t.x < l.left) // baseline 4 px below the line, to centre the digits
            CHECK(std::abs(t.y - 4 - (l.bottom - 1.5 * (l.bottom - l.top) / 4)) <= 0.006);
    }
    CHECK(x_labels == std::set<std::string>{"1", "10", "100", "1000"});
    CHECK(y_labels == std::set<std::string>{"0.001", "0.01", "0.1", "1"});
}

TEST_CASE("plot_svg: labels like 1e-5 and 10000 on long axes, crowded decades are labelled evenly, far enough apart") {
    const plot_options options{"", "", ""};
    const std::vector<plot_series> series{{"wide", {1e-6, 1e6}, {1e-5, 1e4}}};
    const plot_layout l = app::loglog_layout(series, options);
    std::vector<text_element> x_labels;
    std::set<std::string> y_labels;
    for (const auto& t : texts(app::render_loglog_svg(series, options))) {
        if (t.x < l.left) y_labels.insert(t.content);
        if (t.y > l.bottom) x_labels.push_back(t);
    }
    CHECK(y_labels ==
          std::set<std::string>{"1e-5", "1e-4", "0.001", "0.01", "0.1", "1", "10", "100", "1000", "10000"});
    // 13 decades in the width: some labels left out, the rest evenly spaced and not touching.
    REQUIRE(x_labels.size() >= 4);
    CHECK(x_labels.size() < 13);
    CHECK(x_labels.front().content == "1e-6");
    CHECK(x_labels.back().content == "1e6");
    for (size_t i = 1; i < x_labels.size(); ++i) {
        CHECK(x_labels[i].x - x_labels[i - 1].x >= 40);
        CHECK(std::abs((x_labels[i].x - x_labels[i - 1].x) - (x_labels[1].x - x_labels[0].x)) <= 0.02);
    }
}

TEST_CASE("plot_svg: legend names and title are escaped, custom colours used, output well-formed and deterministic") {
    const plot_options options{"RMSE <vs> time & \"spp\"", "seconds", "RMSE"};
    std::vector<plot_series> series{{"a < b & \"c\"", {1, 10}, {1, 0.1}, "#123456"},
                                    {"the book's code, 10 spp", {3}, {0.5}, "", true}};
    const std::string svg = app::render_loglog_svg(series, options);
    CHECK(well_formed(svg));
    CHECK(svg == app::render_loglog_svg(series, options));
    CHECK(svg.find("a < b") == std::string::npos);
    std::set<std::string> contents;
    for (const auto& t : texts(svg)) contents.insert(t.content);
    CHECK(contents.count("a &lt; b &amp; &quot;c&quot;") == 1);
    CHECK(contents.count("the book's code, 10 spp") == 1);
    CHECK(contents.count("RMSE &lt;vs&gt; time &amp; &quot;spp&quot;") == 1);
    CHECK(contents.count("seconds") == 1);
    CHECK(contents.count("RMSE") == 1);
    CHECK(attr(tags(svg, "polyline").at(0), "stroke") == "#123456");
    CHECK(svg.find("fill=\"#ffffff\"") != std::string::npos); // white background
    // The checker itself catches what it is there for.
    CHECK_FALSE(well_formed("<svg><g></svg>"));
    CHECK_FALSE(well_formed("<svg><text>a & b</text></svg>"));
    CHECK_FALSE(well_formed("<svg><text>a < b</text></svg>"));
}

TEST_CASE("plot_svg: every coordinate is written with two decimals") {
    const std::string svg = app::render_loglog_svg({one_over_x()}, plot_options{"t", "x", "y"});
    int checked = 0;
    for (const char* name : {"x", "y", "x1", "y1", "x2", "y2", "cx", "cy", "width", "height"})
        for (const char* element : {"line", "circle", "text"})
            for (const auto& tag : tags(svg, element)) {
                if (tag.find(std::string(" ") + name + "=\"") == std::string::npos) continue;
                std::string v = attr(tag, name);
                CAPTURE(v);
                size_t dot = v.find('.');
                REQUIRE(dot != std::string::npos);
                CHECK(v.size() - dot - 1 == 2);
                ++checked;
            }
    CHECK(checked > 100);
}

TEST_CASE("plot_svg: points with x or y not positive and finite are skipped, and break the line") {
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    std::vector<plot_series> series{
        {"gaps", {1, 10, 0, 100, 1000, 1e4, inf, 1e5}, {1, 0.1, 0.5, -1, 1e-3, 1e-4, 1e-5, nan}}};
    const plot_layout l = app::loglog_layout(series, plot_options{});
    // Ranges from the drawable points only: x 1..1e4, y 1e-4..1.
    CHECK(l.log_x0 == -0.5);
    CHECK(l.log_x1 == 4.5);
    CHECK(l.log_y0 == -4.5);
    CHECK(l.log_y1 == 0.5);
    const std::string svg = app::render_loglog_svg(series, plot_options{});
    CHECK(svg.find("nan") == std::string::npos);
    CHECK(svg.find("inf") == std::string::npos);
    auto lines = tags(svg, "polyline");
    REQUIRE(lines.size() == 2); // (1, 1)-(10, 0.1), then (1000, 1e-3)-(1e4, 1e-4)
    auto first = polyline_points(lines[0]), second = polyline_points(lines[1]);
    REQUIRE(first.size() == 2);
    REQUIRE(second.size() == 2);
    const double decade_w = (l.right - l.left) / 5;
    CHECK(std::abs(first[0].first - (l.left + 0.5 * decade_w)) <= 0.006);
    CHECK(std::abs(second[1].first - (l.left + 4.5 * decade_w)) <= 0.006);
    // Markers (series 0: circles) only on the four drawable points; the legend adds one more.
    CHECK(tags(svg, "circle").size() == 4 + 1);
}

TEST_CASE("plot_svg: a points-only series has a marker at each point and no line") {
    std::vector<plot_series> series{{"single measurements", {0.5, 2, 20}, {0.2, 0.05, 0.01}, "", true}};
    const plot_layout l = app::loglog_layout(series, plot_options{});
    const std::string svg = app::render_loglog_svg(series, plot_options{});
    CHECK(tags(svg, "polyline").empty());
    auto circles = tags(svg, "circle");
    REQUIRE(circles.size() == 3 + 1); // and the legend's
    // x 0.5..20 -> [-0.5, 1.5]; y 0.01..0.2 -> [-2.5, -0.5].
    CHECK(l.log_x0 == -0.5);
    CHECK(l.log_x1 == 1.5);
    CHECK(l.log_y0 == -2.5);
    CHECK(l.log_y1 == -0.5);
    const double xs[] = {0.5, 2, 20}, ys[] = {0.2, 0.05, 0.01};
    for (int i = 0; i < 3; ++i) {
        CHECK(std::abs(num_attr(circles[i], "cx") - (l.left + (std::log10(xs[i]) + 0.5) / 2 * (l.right - l.left))) <= 0.006);
        CHECK(std::abs(num_attr(circles[i], "cy") - (l.bottom - (std::log10(ys[i]) + 2.5) / 2 * (l.bottom - l.top))) <= 0.006);
    }
}

TEST_CASE("plot_svg: the legend covers no data: a free corner inside, else a column to the right, else below") {
    auto inside_legend = [](const plot_layout& l, double x, double y) {
        return x > l.legend_x && x < l.legend_x + l.legend_w && y > l.legend_y && y < l.legend_y + l.legend_h;
    };
    // A falling curve leaves the upper right free.
    {
        const std::vector<plot_series> series{one_over_x()};
        const plot_layout l = app::loglog_layout(series, plot_options{});
        CHECK(l.legend == plot_layout::place::inside);
        CHECK(l.legend_x + l.legend_w <= l.right);
        CHECK(l.legend_y >= l.top);
        CHECK(l.legend_x > (l.left + l.right) / 2);
        CHECK(l.legend_y + l.legend_h < (l.top + l.bottom) / 2);
        for (const auto& p : polyline_points(tags(app::render_loglog_svg(series, plot_options{}), "polyline").at(0)))
            CHECK_FALSE(inside_legend(l, p.first, p.second));
    }
    // Rising, falling and flat lines leave no corner free for a legend this wide.
    {
        plot_series up{"rising, 100 spp", {}, {}}, down{"falling, 100 spp", {}, {}}, flat{"flat, 100 spp", {}, {}};
        for (int i = 0; i <= 20; ++i) {
            double x = std::pow(10.0, i / 10.0);
            up.x.push_back(x), up.y.push_back(x);
            down.x.push_back(x), down.y.push_back(100 / x);
            flat.x.push_back(x), flat.y.push_back(10);
        }
        const plot_layout l = app::loglog_layout({up, down, flat}, plot_options{});
        CHECK(l.legend == plot_layout::place::right);
        CHECK(l.legend_x > l.right);
        CHECK(l.legend_x + l.legend_w <= plot_options{}.width);
        // A narrow chart keeps its plot area wide and puts the legend below the x label.
        plot_options narrow;
        narrow.width = 480, narrow.height = 360;
        const plot_layout n = app::loglog_layout({up, down, flat}, narrow);
        CHECK(n.legend == plot_layout::place::below);
        CHECK(n.right - n.left >= narrow.width / 2);
        CHECK(n.legend_y > n.bottom + 40);
        CHECK(n.legend_y + n.legend_h <= narrow.height);
    }
}

TEST_CASE("plot_svg: no drawable point, x and y of different lengths, or no room: scene_error") {
    CHECK_THROWS_AS(app::render_loglog_svg({}, plot_options{}), rt::scene_error);
    CHECK_THROWS_AS(app::render_loglog_svg({{"empty", {}, {}}}, plot_options{}), rt::scene_error);
    CHECK_THROWS_AS(app::render_loglog_svg({{"non-positive", {0, -1, 2}, {1, 1, 0}}}, plot_options{}), rt::scene_error);
    CHECK_THROWS_AS(app::render_loglog_svg({{"fine", {1, 2}, {1, 2}}, {"mismatched", {1, 2, 3}, {1, 2}}}, plot_options{}),
                    rt::scene_error);
    plot_options tiny;
    tiny.width = 120, tiny.height = 80;
    CHECK_THROWS_AS(app::render_loglog_svg({{"fine", {1, 2}, {1, 2}}}, tiny), rt::scene_error);
}

} // namespace test_plot_svg
