// The same AVX2 passes compiled with AVX-512VL (-mavx2 -mavx512f -mavx512vl): the same 256-bit
// operations in the same order, so the same bits, but with 32 vector registers instead of 16.
// The turning passes keep a block's values in registers instead of spilling them to the stack:
// the turning pyramid of base 40 1.77 -> 1.69 ms/step on one thread, the turning pour of 4 000
// circles 2.26-2.32 -> 2.01-2.12 (an AMD EPYC with AVX-512, 2026-11-30, probes run in turn).
//
// Two runs side by side (Twin) in one 512-bit vector: wide_twin.inl.
#define BALLBOX_TWIN_512_BITS 1
// GCC 12's AVX-512 intrinsics that put halves together or apart (_mm512_insertf64x4,
// _mm512_extractf64x4_pd, the casts between 256 and 512 bits) pass an undefined vector for the
// lanes a mask would keep, which -Wmaybe-uninitialized says may be used; with no mask, none is.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include "solver/wide_passes_4.inl"

namespace engine::detail {

const WidePasses& WidePasses4Evex() { return kPasses; }

}  // namespace engine::detail
