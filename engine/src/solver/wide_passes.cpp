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

bool HasEvexRegisters() {
#if BALLBOX_WIDE_X86
  static const bool has = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl");
  return has;
#else
  return false;
#endif
}

const WidePasses& WidePassesFor(int lanes) {
  const int widest = WidestLanes();
  if (lanes == 0 || lanes > widest) lanes = widest;
#if BALLBOX_WIDE_X86
  if (lanes == 4) return HasEvexRegisters() ? WidePasses4Evex() : WidePasses4();
  if (lanes == 2) return WidePasses2();
#endif
  return WidePasses1();
}

std::vector<const WidePasses*> RunnableWidePasses() {
  std::vector<const WidePasses*> all{&WidePasses1()};
#if BALLBOX_WIDE_X86
  all.push_back(&WidePasses2());
  if (WidestLanes() == 4) all.push_back(&WidePasses4());
  if (WidestLanes() == 4 && HasEvexRegisters()) all.push_back(&WidePasses4Evex());
#endif
  return all;
}

}  // namespace engine::detail
