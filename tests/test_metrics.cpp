// Error metrics (rtweekend/measure/metrics.h) on tiny images whose figures are worked out by hand, the
// 8-bit path through the book's encoding, NaN/Inf handling and size checks.

#include <rtweekend/measure/metrics.h>

#include <doctest/doctest.h>

#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>

namespace test_metrics {

using namespace rt;

namespace {

// An image of `width` x `height` from interleaved RGB values, rows top to bottom.
image make_image(int width, int height, std::initializer_list<float> rgb) {
    image img(width, height);
    REQUIRE(rgb.size() == img.data().size());
    size_t i = 0;
    for (float v : rgb) img.data()[i++] = v;
    return img;
}

loaded_image loaded(image pixels, bool display_encoded) { return loaded_image{std::move(pixels), display_encoded, ""}; }

doctest::Approx near(double v) { return doctest::Approx(v).epsilon(1e-7); }

const float nan_f = std::numeric_limits<float>::quiet_NaN();
const float inf_f = std::numeric_limits<float>::infinity();

// Expects scene_error whose message contains every fragment.
template <class F>
void check_throws_with(F f, std::initializer_list<std::string> fragments) {
    bool threw = false;
    try {
        f();
    } catch (const scene_error& e) {
        threw = true;
        std::string msg = e.what();
        CAPTURE(msg);
        for (const std::string& s : fragments) {
            CAPTURE(s);
            CHECK(msg.find(s) != std::string::npos);
        }
    }
    CHECK(threw);
}

} // namespace

TEST_CASE("metrics: linear RMSE, relMSE, PSNR and bias on a 2x1 image, by hand") {
    // a   = (0.5, 0.25, 1.0)  (0.0, 0.75, 0.25)
    // ref = (0.25, 0.25, 0.5) (0.5, 0.5,  0.25)
    // a - ref = (0.25, 0, 0.5) (-0.5, 0.25, 0); squares 1/16, 0, 1/4, 1/4, 1/16, 0 sum to 5/8.
    //   MSE  = 5/8 / 6 = 5/48,  RMSE = sqrt(5/48) = 0.3227486122
    //   PSNR = 10 log10(1 / (5/48)) = 10 log10(9.6) = 9.822712330 dB
    //   relMSE = (0.0625/(0.0625+0.01) + 0.25/(0.25+0.01) + 0.25/(0.25+0.01) + 0.0625/(0.25+0.01)) / 6
    //          = (0.8620689655 + 0.9615384615 + 0.9615384615 + 0.2403846154) / 6 = 0.5042550840
    //   bias R = (0.25 - 0.5)/2 = -0.125, G = (0 + 0.25)/2 = 0.125, B = (0.5 + 0)/2 = 0.25
    image a = make_image(2, 1, {0.5f, 0.25f, 1.0f, 0.0f, 0.75f, 0.25f});
    image ref = make_image(2, 1, {0.25f, 0.25f, 0.5f, 0.5f, 0.5f, 0.25f});
    image_error e = compare_linear(a, ref);
    CHECK(e.rmse == near(0.3227486122));
    CHECK(e.rel_mse == near(0.5042550840));
    CHECK(e.psnr == near(9.822712330));
    CHECK(e.bias[0] == near(-0.125));
    CHECK(e.bias[1] == near(0.125));
    CHECK(e.bias[2] == near(0.25));
    CHECK(e.peak == 1.0);
    CHECK(e.compared == 6);
    CHECK(e.nonfinite_a == 0);
    CHECK(e.nonfinite_ref == 0);

    // The reference is the second argument: swapping changes relMSE's denominators and the bias sign.
    image_error swapped = compare_linear(ref, a);
    CHECK(swapped.rmse == near(0.3227486122));
    CHECK(swapped.bias[0] == near(0.125));
    CHECK(swapped.rel_mse != near(0.5042550840));
}

TEST_CASE("metrics: identical images give zero error and infinite PSNR") {
    image a = make_image(2, 1, {0.1f, 0.2f, 0.3f, 4.0f, 0.0f, 0.7f});
    for (const image_error& e : {compare_linear(a, a), compare_8bit(a, a), compare_codes(a, a)}) {
        CHECK(e.rmse == 0.0);
        CHECK(e.rel_mse == 0.0);
        CHECK(std::isinf(e.psnr));
        CHECK(e.psnr > 0);
        CHECK(e.bias[0] == 0.0);
        CHECK(e.bias[1] == 0.0);
        CHECK(e.bias[2] == 0.0);
    }
}

TEST_CASE("metrics: 8-bit metrics after the book's encoding, by hand") {
    // byte = int(256 * clamp(sqrt(v), 0, 0.999)):
    //   0.25 -> 0.5 -> 128;  0.5625 -> 0.75 -> 192;  0 -> 0;  0.0625 -> 0.25 -> 64
    // a = (128, 192, 0), ref = (64, 128, 0): differences 64, 64, 0.
    //   MSE = 2 * 64^2 / 3 = 8192/3,  RMSE = 52.25578118,  PSNR = 10 log10(255^2 * 3 / 8192) = 13.76811672 dB
    //   relMSE on codes / 255: ((64/255)^2 / ((64/255)^2 + 0.01) + (64/255)^2 / ((128/255)^2 + 0.01)) / 3
    //        = (0.06299116 / 0.07299116 + 0.06299116 / 0.26196463) / 3 = 0.3678179433
    image a = make_image(1, 1, {0.25f, 0.5625f, 0.0f});
    image ref = make_image(1, 1, {0.0625f, 0.25f, 0.0f});
    image_error e = compare_8bit(a, ref);
    CHECK(e.rmse == near(52.25578118));
    CHECK(e.psnr == near(13.76811672));
    CHECK(e.rel_mse == near(0.3678179433));
    CHECK(e.bias[0] == near(64));
    CHECK(e.bias[1] == near(64));
    CHECK(e.bias[2] == 0.0);
    CHECK(e.peak == 255.0);

    // to_8bit_codes gives the bytes a file would hold: 0.9 -> sqrt 0.948683 -> 242.86 -> 242 (the
    // book truncates), 4 -> clamped to 0.999 -> 255, a negative value -> 0.
    image codes = to_8bit_codes(make_image(1, 1, {0.9f, 4.0f, -1.0f}));
    CHECK(codes.data()[0] == 242.0f);
    CHECK(codes.data()[1] == 255.0f);
    CHECK(codes.data()[2] == 0.0f);

    // compare_codes takes code values as they are: 100 against 90 is RMSE 10, PSNR 20 log10(25.5).
    image_error c = compare_codes(make_image(1, 1, {100, 100, 100}), make_image(1, 1, {90, 90, 90}));
    CHECK(c.rmse == near(10));
    CHECK(c.psnr == near(28.13080360));
    CHECK(c.bias[2] == near(10));
}

TEST_CASE("metrics: NaN and Inf are counted, left out of linear metrics, encoded in 8-bit ones") {
    // a   = (NaN, 0.5, 0.5)  (0.5,  0.5, 0.5)
    // ref = (0.5, 0.5, inf)  (0.25, 0.5, 0.5)
    // Linear: the NaN (a) and the inf (ref) channels are left out; 4 values remain, one differing
    // by 0.25: MSE = 0.0625/4, RMSE 0.125, PSNR 10 log10(64) = 18.06179974 dB,
    // relMSE = (0.0625 / (0.0625 + 0.01)) / 4 = 0.2155172414; bias R = 0.25 (one value), G = B = 0.
    image a = make_image(2, 1, {nan_f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f});
    image ref = make_image(2, 1, {0.5f, 0.5f, inf_f, 0.25f, 0.5f, 0.5f});
    image_error e = compare_linear(a, ref);
    CHECK(e.nonfinite_a == 1);
    CHECK(e.nonfinite_ref == 1);
    CHECK(e.compared == 4);
    CHECK(e.rmse == near(0.125));
    CHECK(e.psnr == near(18.06179974));
    CHECK(e.rel_mse == near(0.2155172414));
    CHECK(e.bias[0] == near(0.25));
    CHECK(e.bias[1] == 0.0);
    CHECK(e.bias[2] == 0.0);

    // 8-bit: NaN -> 0, inf -> 255, 0.5 -> 181, 0.25 -> 128, so a = (0, 181, 181) (181, 181, 181)
    // and ref = (181, 181, 255) (128, 181, 181): differences -181, 0, -74, 53, 0, 0;
    // MSE = (32761 + 5476 + 2809) / 6 = 6841, RMSE 82.71033793, PSNR 10 log10(65025/6841) = 9.779607704 dB;
    // bias R = (-181 + 53)/2 = -64, G = 0, B = -74/2 = -37. Nothing is left out, the counts remain.
    image_error b = compare_8bit(a, ref);
    CHECK(b.compared == 6);
    CHECK(b.nonfinite_a == 1);
    CHECK(b.nonfinite_ref == 1);
    CHECK(b.rmse == near(82.71033793));
    CHECK(b.psnr == near(9.779607704));
    CHECK(b.bias[0] == near(-64));
    CHECK(b.bias[1] == 0.0);
    CHECK(b.bias[2] == near(-37));

    // Nothing left to compare: NaN metrics, not a made-up zero.
    image all_nan = make_image(1, 1, {nan_f, nan_f, nan_f});
    image_error none = compare_linear(all_nan, make_image(1, 1, {0, 0, 0}));
    CHECK(none.compared == 0);
    CHECK(none.nonfinite_a == 3);
    CHECK(std::isnan(none.rmse));
    CHECK(std::isnan(none.psnr));
    CHECK(std::isnan(none.bias[0]));
}

TEST_CASE("metrics: compare_loaded compares like with like") {
    image linear = make_image(1, 1, {0.25f, 0.5625f, 0.0f}); // encodes to (128, 192, 0)
    image codes = make_image(1, 1, {128, 192, 0});

    SUBCASE("two linear images: linear and 8-bit metrics") {
        image_comparison c = compare_loaded(loaded(linear, false), loaded(make_image(1, 1, {0.0625f, 0.25f, 0.0f}), false));
        REQUIRE(c.linear.has_value());
        // Linear differences 0.1875, 0.3125, 0: MSE = (0.03515625 + 0.09765625) / 3 = 0.04427083.
        CHECK(c.linear->rmse == near(std::sqrt(0.1328125 / 3)));
        CHECK(c.display.rmse == near(52.25578118)); // as in the 8-bit hand computation above
    }
    SUBCASE("linear image against its own 8-bit file: no linear metrics, zero 8-bit error") {
        image_comparison c = compare_loaded(loaded(linear, false), loaded(codes, true));
        CHECK_FALSE(c.linear.has_value());
        CHECK(c.display.rmse == 0.0);
        c = compare_loaded(loaded(codes, true), loaded(linear, false));
        CHECK_FALSE(c.linear.has_value());
        CHECK(c.display.rmse == 0.0);
    }
    SUBCASE("two 8-bit images: codes as stored") {
        image_comparison c = compare_loaded(loaded(codes, true), loaded(make_image(1, 1, {118, 192, 0}), true));
        CHECK_FALSE(c.linear.has_value());
        CHECK(c.display.rmse == near(std::sqrt(100.0 / 3)));
        CHECK(c.display.bias[0] == near(10));
    }
    SUBCASE("NaN in a linear input is reported by the 8-bit comparison too") {
        image_comparison c = compare_loaded(loaded(make_image(1, 1, {nan_f, 0.5625f, 0.0f}), false), loaded(codes, true));
        CHECK(c.display.nonfinite_a == 1);
        CHECK(c.display.nonfinite_ref == 0);
        CHECK(c.display.rmse == near(128 / std::sqrt(3.0))); // NaN encodes to 0, against 128
    }
}

TEST_CASE("metrics: images of different sizes or empty images throw, naming the sizes") {
    image a(3, 2), b(2, 3);
    check_throws_with([&] { compare_linear(a, b); }, {"3x2", "2x3"});
    check_throws_with([&] { compare_8bit(a, b); }, {"3x2", "2x3"});
    check_throws_with([&] { compare_codes(a, b); }, {"3x2", "2x3"});
    check_throws_with([&] { compare_loaded(loaded(a, true), loaded(b, false)); }, {"3x2", "2x3"});
    check_throws_with([&] { compare_linear(image(), image()); }, {"empty", "0x0"});
}

TEST_CASE("metrics: error_shares cuts the squared error into cells, by hand") {
    // 3x2 pixels in cells of 2: two columns of cells (x 0-1 and x 2), one row (y 0-1).
    const image ref = make_image(3, 2, {0, 0, 0, 0, 0, 0, 0, 0, 0, //
                                        0, 0, 0, 0, 0, 0, 0, 0, 0});
    const image a = make_image(3, 2, {1, 0, 0, 0, 0, 0, 0, 0, 0,   // (0, 0): R off by 1, squared 1
                                      0, 0, 0, 0, 0, 2, 0, -3, 0}); // (1, 1): B by 2 (4); (2, 1): G by -3 (9)
    const error_map m = error_shares(a, ref, 2);
    CHECK(m.cell == 2);
    CHECK(m.columns == 2);
    CHECK(m.rows == 1);
    REQUIRE(m.share.size() == 2);
    CHECK(m.at(0, 0) == near(5.0 / 14.0));
    CHECK(m.at(1, 0) == near(9.0 / 14.0));

    // Cells of one pixel: each pixel's own share, rows top to bottom.
    const error_map p = error_shares(a, ref, 1);
    CHECK(p.columns == 3);
    CHECK(p.rows == 2);
    CHECK(p.at(0, 0) == near(1.0 / 14.0));
    CHECK(p.at(1, 1) == near(4.0 / 14.0));
    CHECK(p.at(2, 1) == near(9.0 / 14.0));
    CHECK(p.at(1, 0) == 0.0);

    // One cell larger than the image holds everything.
    const error_map whole = error_shares(a, ref, 100);
    CHECK(whole.columns == 1);
    CHECK(whole.rows == 1);
    CHECK(whole.at(0, 0) == near(1.0));
}

TEST_CASE("metrics: error_shares leaves NaN and Inf out, is all zero for equal images, and checks its input") {
    const image ref = make_image(2, 1, {0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f});
    // The only differing values are not finite: nothing is left to share.
    const image bad = make_image(2, 1, {nan_f, 0.5f, 0.5f, 0.5f, inf_f, 0.5f});
    for (const image* a : {&ref, &bad}) {
        const error_map m = error_shares(*a, ref, 1);
        CHECK(m.at(0, 0) == 0.0);
        CHECK(m.at(1, 0) == 0.0);
    }
    // A NaN beside a real difference: the difference takes all.
    const image mixed = make_image(2, 1, {nan_f, 0.5f, 0.5f, 0.5f, 0.25f, 0.5f});
    const error_map m = error_shares(mixed, ref, 1);
    CHECK(m.at(0, 0) == 0.0);
    CHECK(m.at(1, 0) == near(1.0));

    check_throws_with([&] { error_shares(ref, ref, 0); }, {"cells", "0"});
    check_throws_with([&] { error_shares(loaded(image(3, 2), true), loaded(image(2, 3), false), 4); }, {"3x2", "2x3"});
}

TEST_CASE("metrics: error_shares of loaded images compares what compare_loaded compares") {
    // Two linear images: their linear values (squared errors 1 and 3^2 -> 0.1 and 0.9).
    const image lin_ref = make_image(2, 1, {0, 0, 0, 0, 0, 0});
    const image lin_a = make_image(2, 1, {1, 0, 0, 0, 3, 0});
    const error_map lin = error_shares(loaded(lin_a, false), loaded(lin_ref, false), 1);
    CHECK(lin.linear);
    CHECK(lin.at(0, 0) == near(0.1));
    CHECK(lin.at(1, 0) == near(0.9));
    // An 8-bit image against a linear one: codes. The linear reference 0.25 encodes to
    // int(256 * sqrt(0.25)) = 128 in every channel; the 8-bit image is 128 on the left and 138
    // (10 codes off in each channel) on the right, so the right pixel holds all the error.
    const image codes = make_image(2, 1, {128, 128, 128, 138, 138, 138});
    const image quarter = make_image(2, 1, {0.25f, 0.25f, 0.25f, 0.25f, 0.25f, 0.25f});
    const error_map mixed = error_shares(loaded(codes, true), loaded(quarter, false), 1);
    CHECK_FALSE(mixed.linear);
    CHECK(mixed.at(0, 0) == 0.0);
    CHECK(mixed.at(1, 0) == near(1.0));
    check_throws_with([&] { error_shares(image(3, 2), image(2, 3), 4); }, {"3x2", "2x3"});
}

} // namespace test_metrics
