// The peer engines of the side-by-side benchmark, each in its own .cpp built only with
// BALLBOX_BENCH_PEERS (Debian's libbox2d-dev 2.4.1 and libchipmunk-dev 7.0.3).
#pragma once

#include <memory>

#include "bench/peers/scenes.h"

namespace peers {

std::unique_ptr<PhysicsEngine> MakeBox2dEngine();
std::unique_ptr<PhysicsEngine> MakeChipmunkEngine();

}  // namespace peers
