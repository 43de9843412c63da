// A pair of doubles stored in one 16-byte store, packed in registers. Internal to the engine.
//
// A load that two smaller stores make up cannot be forwarded from the store buffer: it waits for
// both to reach the cache. The compiler makes such loads where it stores a pair it holds as two
// scalars as one 16-byte value: it stores the halves on the stack and loads them back whole (a
// rotation returned by ComputeCosSin in two registers), or stores the halves in place for a
// later whole load to read (an anchor made by scalar arithmetic). Packed in registers first, the
// pair is one store, and nothing waits.
#pragma once

#include <cstring>

#include "engine/math.h"
#include "engine/portable_math.h"

namespace engine::detail {

/// Stores (first, second) over the two doubles of `*to` (a Vec2 or a Rot) in one store.
template <typename Pair>
inline void StoreWhole(Pair* to, double first, double second) {
  using Whole = double __attribute__((vector_size(16)));
  static_assert(sizeof(Whole) == sizeof(Pair));
  const Whole whole = {first, second};
  std::memcpy(static_cast<void*>(to), &whole, sizeof whole);
}

inline void StoreWhole(Vec2* to, Vec2 v) { StoreWhole(to, v.x, v.y); }

/// MakeRot(angle) into `*to`, in one store. Out of line as ComputeCosSin is, with its work
/// inline: a pair ComputeCosSin returns in two registers went through the stack on its way
/// into one store, whatever the caller did with it.
[[gnu::noinline]] inline void StoreRot(Rot* to, double angle) {
  const CosSin q = portable_detail::CosSinOf(angle);
  StoreWhole(to, q.c, q.s);
}

}  // namespace engine::detail
