// The engines a side-by-side benchmark compares: ballbox always, and Box2D 2.4 and Chipmunk 7
// when the build found them (BALLBOX_BENCH_PEERS; without it, ballbox's rows alone).
#pragma once

#include <string>
#include <vector>

#include "bench/peers/ballbox_engine.h"
#include "bench/peers/scenes.h"
#if defined(BALLBOX_PEER_BOX2D) || defined(BALLBOX_PEER_CHIPMUNK)
#include "bench/peers/peer_engines.h"
#endif

namespace peers {

struct EngineEntry {
  std::string name;
  EngineFactory make;
};

/// ballbox at its default settings first (the ratios are to it), then every peer built in.
inline std::vector<EngineEntry> Engines() {
  std::vector<EngineEntry> out;
  out.push_back({"ballbox", [] { return std::make_unique<BallboxEngine>(); }});
  // The same on two threads (WorldDef::threads): the same bits, in less time on large scenes.
  out.push_back({"ballbox 2 threads", [] {
                   return std::make_unique<BallboxEngine>(BallboxSetting{engine::ContactSolver::kSubstep, 0, 2});
                 }});
#ifdef BALLBOX_PEER_BOX2D
  out.push_back({"Box2D 2.4.1", [] { return MakeBox2dEngine(); }});
#endif
#ifdef BALLBOX_PEER_CHIPMUNK
  out.push_back({"Chipmunk 7.0.3", [] { return MakeChipmunkEngine(); }});
#endif
  return out;
}

/// The peers missing from this build, for the note under the table.
inline std::string MissingPeers() {
  std::string missing;
#ifndef BALLBOX_PEER_BOX2D
  missing += "Box2D 2.4.1";
#endif
#ifndef BALLBOX_PEER_CHIPMUNK
  missing += std::string(missing.empty() ? "" : " and ") + "Chipmunk 7.0.3";
#endif
  return missing;
}

}  // namespace peers
