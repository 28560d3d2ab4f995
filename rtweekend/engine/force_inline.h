#pragma once
// RTWEEKEND_FORCE_INLINE: for the functions of the hot loop that must be inlined into their caller:
// the leaf kernels and the shape-kind dispatch, into the BVH walk. The compiler's own limits
// decline them once the walk grows large, and the call then costs more than it saves: about 3 %
// of the cover scene's instructions (callgrind, an AVX2 build) and 1 % of its time.

#if defined(__GNUC__)
#define RTWEEKEND_FORCE_INLINE inline __attribute__((always_inline))
#else
#define RTWEEKEND_FORCE_INLINE inline
#endif
