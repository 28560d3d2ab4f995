// libFuzzer harness: sample slices (render --samples A:B -o part.pfm, rtweekend/io/slice_file.h),
// what merge reads.
//
// The input is a slice file, read from memory by rt::decode_slice. A slice it accepts must survive
// a round trip: encoded again (rt::encode_slice) and read back, every field and sum is the same,
// and a merger takes it (its image is then the slice's own mean). A refused file must give one
// clear error line.

#include "fuzz_support.h"

#include <rtweekend/io/slice_file.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

[[noreturn]] void broken(const char* what) {
    std::fprintf(stderr, "fuzz: an accepted slice %s\n", what);
    std::abort();
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string input = fuzz::bytes(data, size);
    rt::sample_slice slice;
    try {
        slice = rt::decode_slice(input, "fuzz.pfm");
    } catch (const rt::scene_error& e) {
        fuzz::refused(e);
        return 0;
    }
    rt::sample_slice again;
    try {
        again = rt::decode_slice(rt::encode_slice(slice), "again.pfm");
    } catch (const rt::scene_error&) {
        broken("does not read back once written again");
    }
    const rt::slice_render& a = slice.render;
    const rt::slice_render& b = again.render;
    if (a.width != b.width || a.height != b.height || a.samples_per_pixel != b.samples_per_pixel || a.seed != b.seed ||
        a.sampler != b.sampler || a.settings != b.settings || a.scene != b.scene ||
        slice.first_sample != again.first_sample || slice.end_sample != again.end_sample || slice.rays != again.rays ||
        slice.nonfinite != again.nonfinite || slice.saturated != again.saturated || slice.sums != again.sums)
        broken("reads back different once written again");
    try {
        rt::slice_merger merger;
        merger.add(slice, "fuzz.pfm");
    } catch (const rt::scene_error& e) {
        fuzz::refused(e); // a lone slice may still be refused (it must say why in one line)
    }
    return 0;
}
