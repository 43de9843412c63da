// The wide passes four lanes wide, compiled for AVX2 alone (-mavx2, not FMA).
#include "solver/wide_passes_4.inl"

namespace engine::detail {

const WidePasses& WidePasses4() { return kPasses; }

}  // namespace engine::detail
