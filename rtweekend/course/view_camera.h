#pragma once
// view_camera: the camera of the CENG795 course scenes (course/whitted_scene.h holds them; the
// XML reader, io/xml_scene.h, fills them in), and the path tracer's camera_frame for one.

#include "../core/scene_error.h"
#include "../image/tonemap.h"
#include "../render/camera_frame.h"
#include "../vec3.h"

#include <cmath>
#include <string>

namespace rt {

// A CENG795 camera: position e, gaze, up, the image plane's extent (left, right, bottom, top) at
// distance near_distance along the gaze, and the image size. Pixel (i, j), j = 0 the top row,
// is sampled once, at its centre (see whitted.h for the mapping).
struct view_camera {
    point3 position{0, 0, 0};
    vec3 gaze{0, 0, -1};
    vec3 up{0, 1, 0};
    double left = -1, right = 1, bottom = -1, top = 1;
    double near_distance = 1;
    int width = 0, height = 0;
    std::string image_name; // as the file gives it; .png, .ppm, .pfm or .exr
    // handedness="left": u = w x up instead of up x w, the image mirrored left to right (v as before).
    bool left_handed = false;
    // Distribution ray tracing (homework 3): samples per pixel (NumSamples: jittered on a
    // sqrt(N) x sqrt(N) grid when N is a square, else uniform in the pixel; 1 is the pixel's
    // centre), and a square lens of edge `aperture` in the u-v plane whose rays meet on the plane
    // at `focus_distance` along the gaze (0: a pinhole). course/whitted.h takes them.
    int samples = 1;
    double aperture = 0, focus_distance = 0;
    // <Tonemap> (homework 5): the image is written linear (EXR) and as a PNG through the
    // photographic operator (image/tonemap.h); write_course_image (course/whitted.h) writes both.
    bool tonemapped = false;
    photographic_tonemap tonemap;
    // <Renderer>PathTracing</Renderer> (homework 6): the course's path tracer instead of the classic
    // recursive one (course/whitted.h, "The course's path tracer"), with the <RendererParams> it
    // names: next-event estimation, cosine-weighted (rather than uniform) hemisphere sampling, and
    // Russian roulette (which lifts the depth limit).
    struct path_tracing_t {
        bool on = false;
        bool next_event_estimation = false, importance_sampling = false, russian_roulette = false;
    } path_tracing;
};

// The frame of a CENG795 course camera (above): the image plane at near_distance along
// the gaze, spanning [left, right] x [bottom, top]; pixel (i, j), j = 0 the top row, centred at
// e - d w + (l + (i + 0.5)(r - l)/nx) u + (t - (j + 0.5)(t - b)/ny) v, with w = -gaze,
// u = unit(up x w), v = w x u (a left-handed camera then turns u round: u = unit(w x up)). With
// an aperture, a thin lens focused at focus_distance (below). Throws scene_error for settings
// that make no image.
inline camera_frame view_camera_frame(const view_camera& c) {
    auto finite = [](const vec3& a) { return std::isfinite(a.x()) && std::isfinite(a.y()) && std::isfinite(a.z()); };
    if (c.width <= 0 || c.height <= 0 || c.width > (1 << 16) || c.height > (1 << 16))
        throw scene_error("image resolution must be between 1 and 65536, got " + std::to_string(c.width) + "x" +
                          std::to_string(c.height));
    if (!finite(c.position) || !finite(c.gaze) || !finite(c.up) ||
        !std::isfinite(c.left + c.right + c.bottom + c.top + c.near_distance))
        throw scene_error("camera settings must be finite numbers");
    const vec3 w = -unit_vector(c.gaze);
    const vec3 right_u = unit_vector(cross(c.up, w));
    const vec3 v = cross(w, right_u);
    const vec3 u = c.left_handed ? -right_u : right_u;
    if (!finite(u) || !finite(w)) throw scene_error("camera gaze and up must be non-zero and not parallel");
    const vec3 du = (c.right - c.left) / c.width * u, dv = -(c.top - c.bottom) / c.height * v;
    camera_frame f;
    f.width = c.width;
    f.height = c.height;
    f.position = c.position;
    // A lens (aperture > 0): the same pixel grid moved out along the pinhole rays to the focal
    // plane at focus_distance, where the renderer's thin lens makes its rays meet (the course's
    // t_fd = focus / dot(dir, -w)); the lens a disk of diameter `aperture` about e in the u-v plane,
    // which the course allows for its square (ceng795-later.md, 3.2).
    double grid = 1;
    if (c.aperture > 0) {
        if (!std::isfinite(c.aperture) || !(c.focus_distance > 0) || !std::isfinite(c.focus_distance) || !(c.near_distance > 0))
            throw scene_error("camera aperture must be finite, with a positive focus distance and near distance");
        grid = c.focus_distance / c.near_distance;
        f.thin_lens = true;
        f.defocus_disk_u = vec3f(0.5 * c.aperture * u);
        f.defocus_disk_v = vec3f(0.5 * c.aperture * v);
    }
    f.pixel00 = vec3f(grid * (-c.near_distance * w + c.left * u + c.top * v + 0.5 * (du + dv)));
    f.pixel_delta_u = vec3f(grid * du);
    f.pixel_delta_v = vec3f(grid * dv);
    return f;
}

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::view_camera;
#endif
