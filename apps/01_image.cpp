// 01_image: the first picture, with no rays at all (book section 2, "Output an Image").
//
// Each pixel's colour is computed from its position: red grows from 0 at the left edge to 1 at
// the right, green from 0 at the top row to 1 at the bottom row (rows are counted from the top,
// as in the book's loop), blue stays 0. So the top-left corner is black, the top-right red, the
// bottom-left green and the bottom-right yellow.
//
// We fill an rt::image directly. Its values are linear; the writers apply gamma 2 (a square
// root) when they encode bytes, which the book only introduces in section 9.5. Our gradient
// therefore comes out brighter in the middle than the book's first figure, which writes the raw
// values with int(255.999 * x). The corners are the same.
//
//   01_image > image.ppm                 256x256, P3 PPM on stdout
//   01_image --width 512 -o image.png    square, 512x512
//
// --spp, --depth, --threads and --seed are accepted but mean nothing here: nothing is sampled.

#include <rtweekend/rtweekend.h>

#include "app_options.h"

int main(int argc, char** argv) {
    const app::description d{"01_image", "Writes the book's first image: a red-green gradient, no rays.", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        // Image: 256x256 like the book, or --width N for an N x N square.
        int image_width = opt.width.value_or(256);
        int image_height = image_width;

        rt::image img(image_width, image_height);
        for (int j = 0; j < image_height; j++) { // j = 0 is the top row
            for (int i = 0; i < image_width; i++) {
                // A one-pixel image has no extent to spread the gradient over: use 0.
                double r = image_width > 1 ? double(i) / (image_width - 1) : 0.0;
                double g = image_height > 1 ? double(j) / (image_height - 1) : 0.0;
                double b = 0.0;
                img.set_pixel(i, j, rt::color(r, g, b));
            }
        }

        app::write_output(opt, img);
    });
}
