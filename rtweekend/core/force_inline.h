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

// RTWEEKEND_UNROLL(n), before a loop of n trips over the axes or lanes of the hot loop whose body
// should be laid out n times, so that its arrays of vectors live in registers. g++ does that at
// -O3 (-fpeel-loops) but not at -O2, the level a learner's own build often uses, where the cover
// then ran about 10 % slower.
#if defined(__clang__)
#define RTWEEKEND_PRAGMA(x) _Pragma(#x)
#define RTWEEKEND_UNROLL(n) RTWEEKEND_PRAGMA(unroll n)
#elif defined(__GNUC__)
#define RTWEEKEND_PRAGMA(x) _Pragma(#x)
#define RTWEEKEND_UNROLL(n) RTWEEKEND_PRAGMA(GCC unroll n)
#else
#define RTWEEKEND_UNROLL(n)
#endif
