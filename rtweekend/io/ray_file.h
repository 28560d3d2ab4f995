#pragma once
// Ray files (.rays): a fixed batch of rays, so that two ray tracers can be timed on exactly the
// same work and their answers compared. The format (shared/formats/rays.md) is little-endian:
//
//   offset  size        field
//   0       8           magic "RTRAYS1\0"
//   8       4           uint32 kind: 0 = closest hit (report t), 1 = any hit (occlusion)
//   12      4           uint32 reserved, 0
//   16      8           uint64 count
//   24      32 * count  per ray, 8 float32: ox oy oz tmin dx dy dz tmax
//
//   read_rays(path)          the whole file, checked; throws scene_error naming the path
//   write_rays(path, batch)  checks the batch, then writes through a temporary file and a rename,
//                            so a reader never sees half a file
//   encode_rays / decode_rays  the same on bytes in memory
//
// What a well-formed file holds, and therefore what both directions check: finite origins,
// directions of unit length (within 1e-3: a file written with the wrong byte order or a stale
// layout fails here rather than producing plausible timings), 0 <= tmin <= tmax, tmin finite,
// tmax finite or +infinity. The count must match the file size exactly.

#include "../core/vec3f.h"
#include "../core/scene_error.h"
#include "../core/file.h"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <string>
#include <system_error>
#include <vector>

namespace rt {

enum class ray_query : uint32_t { closest = 0, any = 1 };

struct ray_batch {
    ray_query kind = ray_query::closest;
    std::vector<ray3f> rays;
};

inline constexpr char ray_file_magic[8] = {'R', 'T', 'R', 'A', 'Y', 'S', '1', '\0'};
inline constexpr size_t ray_file_header_bytes = 24;
inline constexpr size_t ray_file_record_bytes = 32;

inline const char* ray_query_name(ray_query kind) { return kind == ray_query::any ? "any" : "closest"; }

namespace detail {

// Byte order is spelled out byte by byte, so the files are the same on any host; compilers turn
// these loops into plain loads and stores on little-endian machines.
inline void put_u32_le(std::string& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(char((v >> (8 * i)) & 0xffu));
}
inline void put_u64_le(std::string& out, uint64_t v) {
    for (int i = 0; i < 8; ++i) out.push_back(char((v >> (8 * i)) & 0xffu));
}
inline void put_f32_le(std::string& out, float f) {
    uint32_t bits;
    std::memcpy(&bits, &f, 4);
    put_u32_le(out, bits);
}
inline uint32_t get_u32_le(const unsigned char* p) {
    return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
}
inline uint64_t get_u64_le(const unsigned char* p) { return uint64_t(get_u32_le(p)) | (uint64_t(get_u32_le(p + 4)) << 32); }
inline float get_f32_le(const unsigned char* p) {
    uint32_t bits = get_u32_le(p);
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
}

// Empty if `r` is a ray a well-formed file may hold, otherwise what is wrong with it.
inline std::string ray_problem(const ray3f& r) {
    const float c[8] = {r.origin.x, r.origin.y, r.origin.z, r.tmin, r.dir.x, r.dir.y, r.dir.z, r.tmax};
    for (float v : c)
        if (std::isnan(v)) return "has a NaN component";
    if (!is_finite(r.origin)) return "has an infinite origin";
    if (!is_finite(r.dir)) return "has an infinite direction";
    double len = std::sqrt(double(r.dir.x) * r.dir.x + double(r.dir.y) * r.dir.y + double(r.dir.z) * r.dir.z);
    if (!(std::fabs(len - 1.0) <= 1e-3)) return "has a direction of length " + number_text(len) + ", not 1";
    if (!std::isfinite(r.tmin) || r.tmin < 0) return "has tmin " + number_text(r.tmin) + " (must be finite and >= 0)";
    if (r.tmax < r.tmin) return "has tmax " + number_text(r.tmax) + " below tmin " + number_text(r.tmin);
    return {};
}

} // namespace detail

// The file contents for `batch`; `name` (the destination) appears in the error for a bad ray.
inline std::string encode_rays(const ray_batch& batch, const std::string& name = "rays") {
    if (batch.kind != ray_query::closest && batch.kind != ray_query::any)
        throw scene_error("cannot write '" + name + "': unknown ray kind " + std::to_string(uint32_t(batch.kind)));
    std::string out;
    out.reserve(ray_file_header_bytes + ray_file_record_bytes * batch.rays.size());
    out.append(ray_file_magic, sizeof ray_file_magic);
    detail::put_u32_le(out, uint32_t(batch.kind));
    detail::put_u32_le(out, 0);
    detail::put_u64_le(out, uint64_t(batch.rays.size()));
    for (size_t i = 0; i < batch.rays.size(); ++i) {
        const ray3f& r = batch.rays[i];
        std::string problem = detail::ray_problem(r);
        if (!problem.empty()) throw scene_error("cannot write '" + name + "': ray " + std::to_string(i) + " " + problem);
        for (float v : {r.origin.x, r.origin.y, r.origin.z, r.tmin, r.dir.x, r.dir.y, r.dir.z, r.tmax})
            detail::put_f32_le(out, v);
    }
    return out;
}

// Parses the contents of a ray file; `name` (the file it came from) starts every error message.
inline ray_batch decode_rays(const std::string& bytes, const std::string& name = "rays") {
    auto fail = [&](const std::string& problem) { return scene_error("'" + name + "': " + problem); };
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
    if (bytes.size() < ray_file_header_bytes)
        throw fail("truncated header: " + std::to_string(bytes.size()) + " bytes, a ray file starts with " +
                   std::to_string(ray_file_header_bytes));
    if (std::memcmp(p, ray_file_magic, sizeof ray_file_magic) != 0) throw fail("not a ray file (bad magic, expected RTRAYS1)");
    uint32_t kind = detail::get_u32_le(p + 8);
    if (kind > uint32_t(ray_query::any)) throw fail("unknown ray kind " + std::to_string(kind) + " (expected 0 or 1)");
    uint32_t reserved = detail::get_u32_le(p + 12);
    if (reserved != 0) throw fail("reserved field is " + std::to_string(reserved) + ", expected 0");
    uint64_t count = detail::get_u64_le(p + 16);
    uint64_t payload = bytes.size() - ray_file_header_bytes;
    // Compare by division: count * 32 may overflow for a corrupt count.
    if (payload % ray_file_record_bytes != 0 || count != payload / ray_file_record_bytes)
        throw fail("header says " + std::to_string(count) + " rays but the file holds " + std::to_string(payload) +
                   " bytes of rays (" + std::to_string(ray_file_record_bytes) + " per ray)");

    ray_batch batch;
    batch.kind = ray_query(kind);
    batch.rays.resize(size_t(count));
    const unsigned char* rec = p + ray_file_header_bytes;
    for (size_t i = 0; i < batch.rays.size(); ++i, rec += ray_file_record_bytes) {
        ray3f& r = batch.rays[i];
        r.origin = {detail::get_f32_le(rec), detail::get_f32_le(rec + 4), detail::get_f32_le(rec + 8)};
        r.tmin = detail::get_f32_le(rec + 12);
        r.dir = {detail::get_f32_le(rec + 16), detail::get_f32_le(rec + 20), detail::get_f32_le(rec + 24)};
        r.tmax = detail::get_f32_le(rec + 28);
        std::string problem = detail::ray_problem(r);
        if (!problem.empty()) throw fail("ray " + std::to_string(i) + " " + problem);
    }
    return batch;
}

inline ray_batch read_rays(const std::string& path) {
    return decode_rays(read_file(path, "ray file"), path);
}

inline void write_rays(const std::string& path, const ray_batch& batch) {
    write_file_atomically(path, encode_rays(batch, path));
}

} // namespace rt
