// Choosing the wide passes' width for this processor.
#include "solver/wide_passes.h"

namespace engine::detail {

int WidestLanes() {
#if BALLBOX_WIDE_X86
  static const int widest = __builtin_cpu_supports("avx2") ? 4 : 2;
  return widest;
#else
  return 1;
#endif
}

const WidePasses& WidePassesFor(int lanes) {
  const int widest = WidestLanes();
  if (lanes == 0 || lanes > widest) lanes = widest;
#if BALLBOX_WIDE_X86
  if (lanes == 4) return WidePasses4();
  if (lanes == 2) return WidePasses2();
#endif
  return WidePasses1();
}

}  // namespace engine::detail
