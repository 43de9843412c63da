// The dynamic AABB tree broad phase: a leaf per body with a fattened box, reinserted only when the
// body leaves it; pairs from one traversal of the tree against itself.
//
// The ideas follow Erin Catto's b2DynamicTree (Box2D 2.x; "Dynamic Bounding Volume Hierarchies",
// GDC 2019): insertion descends by a surface-area (here perimeter) cost with branch and bound,
// ancestors are refitted on the way up and rotated where a swap shrinks a box.
#include "broad_phase/aabb_tree.h"

#include <algorithm>
#include <cmath>

#include "broad_phase/pair_sort.h"

namespace engine {

namespace {

// Fewer candidates than this are checked on one thread, and fewer leaves marked, built and
// traversed on one: the hand-off would cost more.
constexpr std::uint32_t kMinSharedCandidates = 4096;
constexpr std::uint32_t kMinSharedLeaves = 2048;

// A leaf's box is the body's grown by this fraction of its larger side, so that small motions
// (a pile settling, a contact jittering) stay inside it and cost nothing.
constexpr double kMarginFraction = 0.1;
// And stretched this many times the body's last displacement ahead of it, so that a steadily
// moving body (a falling one) is reinserted every few steps rather than every step. The stretch
// is capped at twice the body's size so that a teleport does not leave a long box behind.
constexpr double kPredictSteps = 4.0;
// A fat box more than this many times the perimeter a new one would get is rebuilt. A body moving
// steadily gets about the same box again, so it is left alone; a stopped one sheds the stretch.
constexpr double kLooseFactor = 1.5;
// Fresh pairs are sorted by counting (SortPairs) from one pair for this many bodies: below, the
// counts' pass over every body costs more than std::sort's comparisons.
constexpr std::size_t kBodiesPerCountedPair = 16;

// Whether two boxes overlap, the four comparisons joined without a branch: which candidates
// overlap is as good as random (fat boxes overlap where the boxes do not), and a mispredicted
// branch costs more than the comparisons.
bool OverlapsJoined(const AABB& a, const AABB& b) {
  return (a.lower.x <= b.upper.x) & (b.lower.x <= a.upper.x) & (a.lower.y <= b.upper.y) & (b.lower.y <= a.upper.y);
}

// The pairs whose boxes overlap into the front of `out` (grown to hold all of them), and how
// many: every pair is written, the count advancing past the overlapping ones, so no branch.
std::size_t OverlappingInto(std::span<const BodyPair> pairs, std::span<const AABB> boxes,
                            std::vector<BodyPair>* out) {
  if (out->size() < pairs.size()) out->resize(pairs.size());
  BodyPair* kept = out->data();
  std::size_t count = 0;
  for (const BodyPair p : pairs) {
    kept[count] = p;
    count += OverlapsJoined(boxes[p.a], boxes[p.b]) ? 1 : 0;
  }
  return count;
}

double Perimeter(const AABB& b) { return 2.0 * ((b.upper.x - b.lower.x) + (b.upper.y - b.lower.y)); }

AABB Union(const AABB& a, const AABB& b) {
  return {{std::min(a.lower.x, b.lower.x), std::min(a.lower.y, b.lower.y)},
          {std::max(a.upper.x, b.upper.x), std::max(a.upper.y, b.upper.y)}};
}

bool Contains(const AABB& outer, const AABB& inner) {
  return outer.lower.x <= inner.lower.x && outer.lower.y <= inner.lower.y && inner.upper.x <= outer.upper.x &&
         inner.upper.y <= outer.upper.y;
}

bool SameBox(const AABB& a, const AABB& b) { return a.lower == b.lower && a.upper == b.upper; }

}  // namespace

AABB AabbTree::FatBox(const AABB& box, const AABB& previous, bool* stretched) const {
  const double size = std::max(box.upper.x - box.lower.x, box.upper.y - box.lower.y);
  const double margin = kMarginFraction * size;
  AABB fat{box.lower - Vec2{margin, margin}, box.upper + Vec2{margin, margin}};
  const Vec2 moved = 0.5 * (box.lower + box.upper) - 0.5 * (previous.lower + previous.upper);
  const double dx = Clamp(kPredictSteps * moved.x, -2.0 * size, 2.0 * size);
  const double dy = Clamp(kPredictSteps * moved.y, -2.0 * size, 2.0 * size);
  (dx < 0.0 ? fat.lower.x : fat.upper.x) += dx;
  (dy < 0.0 ? fat.lower.y : fat.upper.y) += dy;
  // Stretched by no more than the margin, a fat box can never become too loose (see kLooseFactor).
  *stretched = std::max(std::abs(dx), std::abs(dy)) > margin;
  return fat;
}

std::int32_t AabbTree::Allocate() {
  std::int32_t node;
  if (free_list_ != kNull) {
    node = free_list_;
    free_list_ = nodes_[node].parent;  // free nodes chain through `parent`
  } else {
    node = static_cast<std::int32_t>(nodes_.size());
    nodes_.emplace_back();
  }
  nodes_[node] = Node{};
  return node;
}

void AabbTree::Free(std::int32_t node) {
  nodes_[node].parent = free_list_;
  nodes_[node].height = -1;
  free_list_ = node;
}

void AabbTree::Clear() {
  nodes_.clear();
  root_ = kNull;
  free_list_ = kNull;
  leaf_of_.clear();
  previous_.clear();
  candidates_.clear();
  crowded_ = false;
  reinserts_since_relayout_ = 0;
}

// Branch and bound down from `start`: stop at a node when making it the sibling is cheaper than
// the best each child could offer (every ancestor on the way grows by `inheritance` either way).
std::int32_t AabbTree::FindBestSibling(const AABB& box, std::int32_t start) const {
  std::int32_t index = start;
  while (!nodes_[index].IsLeaf()) {
    const Node& node = nodes_[index];
    const double perimeter = Perimeter(node.box);
    const double combined = Perimeter(Union(node.box, box));
    const double here = 2.0 * combined;
    const double inheritance = 2.0 * (combined - perimeter);
    auto descend = [&](std::int32_t child) {
      const Node& c = nodes_[child];
      const double grown = Perimeter(Union(box, c.box));
      return (c.IsLeaf() ? grown : grown - Perimeter(c.box)) + inheritance;
    };
    const double cost1 = descend(node.child1);
    const double cost2 = descend(node.child2);
    if (here < cost1 && here < cost2) break;
    index = cost1 <= cost2 ? node.child1 : node.child2;
  }
  return index;
}

void AabbTree::InsertLeaf(std::int32_t leaf) {
  if (root_ == kNull) {
    root_ = leaf;
    nodes_[leaf].parent = kNull;
    return;
  }
  AttachLeaf(leaf, Allocate(), root_, kNull);
}

void AabbTree::AttachLeaf(std::int32_t leaf, std::int32_t parent, std::int32_t start, std::int32_t top, int top_side) {
  const AABB box = nodes_[leaf].box;
  const std::int32_t sibling = FindBestSibling(box, start);
  const std::int32_t old_parent = nodes_[sibling].parent;
  Node& p = nodes_[parent];
  p = Node{};
  p.parent = old_parent;
  p.box = Union(box, nodes_[sibling].box);
  p.height = nodes_[sibling].height + 1;
  p.child1 = sibling;
  p.child2 = leaf;
  nodes_[sibling].parent = parent;
  nodes_[leaf].parent = parent;
  if (old_parent == kNull) {
    root_ = parent;
  } else if (old_parent == top && top_side >= 0) {
    ChildLink(top, top_side) = parent;
  } else if (nodes_[old_parent].child1 == sibling) {
    nodes_[old_parent].child1 = parent;
  } else {
    nodes_[old_parent].child2 = parent;
  }
  RefitUpward(old_parent, top);  // the new parent's box and height are already right
}

void AabbTree::RemoveLeaf(std::int32_t leaf) {
  if (leaf == root_) {
    root_ = kNull;
    return;
  }
  Free(DetachLeaf(leaf, kNull));
}

std::int32_t AabbTree::DetachLeaf(std::int32_t leaf, std::int32_t top, int top_side) {
  const std::int32_t parent = nodes_[leaf].parent;
  const std::int32_t grandparent = nodes_[parent].parent;
  const std::int32_t sibling = nodes_[parent].child1 == leaf ? nodes_[parent].child2 : nodes_[parent].child1;
  nodes_[sibling].parent = grandparent;
  if (grandparent == kNull) {
    root_ = sibling;
    return parent;
  }
  if (grandparent == top && top_side >= 0) {
    ChildLink(top, top_side) = sibling;
  } else if (nodes_[grandparent].child1 == parent) {
    nodes_[grandparent].child1 = sibling;
  } else {
    nodes_[grandparent].child2 = sibling;
  }
  RefitUpward(grandparent, top);
  return parent;
}

void AabbTree::RefitUpward(std::int32_t node, std::int32_t top) {
  while (node != top) {
    Node& n = nodes_[node];
    const AABB old_box = n.box;
    const std::int32_t old_height = n.height;
    n.box = Union(nodes_[n.child1].box, nodes_[n.child2].box);
    Rotate(node);
    n.height = 1 + std::max(nodes_[n.child1].height, nodes_[n.child2].height);
    // A node that kept its box and height changes nothing above it: most moves end a few levels up.
    if (SameBox(n.box, old_box) && n.height == old_height) break;
    node = n.parent;
  }
}

// A tree rotation that swaps one child of `a` with a grandchild on the other side when that
// shrinks the perimeter of the other side (Kopta et al., "Fast, Effective BVH Updates for
// Animated Scenes", I3D 2012; Box2D v3 does the same). a's own box keeps the same leaves. Rotating
// for height instead (AVL) keeps the tree shallow but lets sibling boxes overlap more, and the
// pair traversal pays for overlap, not for depth.
void AabbTree::Rotate(std::int32_t a) {
  const std::int32_t b = nodes_[a].child1;
  const std::int32_t c = nodes_[a].child2;
  // Candidates in a fixed order, the first strict best wins: (child of a, its sibling, grandchild
  // under that sibling, the grandchild's sibling).
  std::int32_t best_child = kNull, best_grandchild = kNull;
  double best_gain = 0.0;
  auto consider = [&](std::int32_t child, std::int32_t other) {
    const Node& o = nodes_[other];
    if (o.IsLeaf()) return;
    const double base = Perimeter(o.box);
    const std::int32_t grandchildren[2] = {o.child1, o.child2};
    for (int k = 0; k < 2; ++k) {
      // `child` moves under `other` in place of grandchildren[k], next to grandchildren[1 - k].
      const double gain = base - Perimeter(Union(nodes_[child].box, nodes_[grandchildren[1 - k]].box));
      if (gain > best_gain) {
        best_gain = gain;
        best_child = child;
        best_grandchild = grandchildren[k];
      }
    }
  };
  consider(b, c);
  consider(c, b);
  if (best_child == kNull) return;

  const std::int32_t other = best_child == b ? c : b;
  Node& node_a = nodes_[a];
  Node& node_o = nodes_[other];
  (node_a.child1 == best_child ? node_a.child1 : node_a.child2) = best_grandchild;
  (node_o.child1 == best_grandchild ? node_o.child1 : node_o.child2) = best_child;
  nodes_[best_grandchild].parent = a;
  nodes_[best_child].parent = other;
  node_o.box = Union(nodes_[node_o.child1].box, nodes_[node_o.child2].box);
  node_o.height = 1 + std::max(nodes_[node_o.child1].height, nodes_[node_o.child2].height);
}

void AabbTree::FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                         std::span<const PairQuota> quotas, detail::WorkerPool* pool) {
  collector_.Begin(boxes, quotas, pairs);
  if (boxes.size() < leaf_of_.size()) Clear();  // bodies went away: start over
  const std::size_t n = boxes.size();
  moved_.assign(n, 0);
  moved_list_.clear();
  MarkMovedLeaves(boxes, pool);
  if (4 * moved_list_.size() > n) {
    Rebuild(boxes, pool);
  } else {
    ReinsertMovedLeaves(boxes, pool);
    reinserts_since_relayout_ += moved_list_.size();
    if (2 * reinserts_since_relayout_ > n) {
      Relayout();
      reinserts_since_relayout_ = 0;
    }
  }
  last_reinserts_ = moved_list_.size();
  previous_.assign(boxes.begin(), boxes.end());
  forget_motion_ = false;

  const bool found = RefreshCandidates(boxes, pool);
  if (!crowded_) {  // a crowded tree handed its pairs over already
    if (found) {
      CollectFound(pool);
    } else {
      AddOverlappingCandidates(boxes, pool);
    }
  }
  collector_.Finish();
}

// Which leaves go back in is found for all first (on the pool's threads: marks are per body), in
// id order into moved_list_, the bodies the tree has not seen yet among them.
void AabbTree::MarkMovedLeaves(std::span<const AABB> boxes, detail::WorkerPool* pool) {
  const auto known = static_cast<std::uint32_t>(leaf_of_.size());
  const auto mark = [&](std::uint32_t i) {
    const Node& node = nodes_[leaf_of_[i]];
    // A body that left its fat box goes back in with a new one; so does one that has slowed down
    // a lot (its box stretched for a motion it no longer has would cost pair tests every step).
    if (!Contains(node.box, boxes[i])) {
      moved_[i] = 1;
    } else if (node.stretched) {
      bool stretched = false;
      const AABB fat = FatBox(boxes[i], PreviousBox(boxes, i), &stretched);
      moved_[i] = Perimeter(node.box) > kLooseFactor * Perimeter(fat) ? 1 : 0;
    }
  };
  detail::ForEachIndexInRuns(pool, known, kMinSharedLeaves, mark);  // the tree: last changed on thread 0
  for (std::uint32_t i = known; i < boxes.size(); ++i) moved_[i] = 1;
  for (std::uint32_t i = 0; i < boxes.size(); ++i) {
    if (moved_[i]) moved_list_.push_back(i);
  }
}

// Few moved: each goes back in alone, in id order (reinserting one leaf changes only inner nodes,
// never another leaf's box), and new bodies get leaves of their own. Shared, the tree's top is
// cut into branches (FindBranches), whose moved leaves go back into them, branch by branch, each
// branch to whichever thread is free, those with the most first; then the nodes above the
// branches are refitted, and the leaves outside any branch go back one by one. (Two subtrees
// side by side, one a thread, took back 52 and 168 leaves a call in bench_threads' window of
// the 4 000-circle pour, whose top is still settling: the first thread waited 123 kcyc a call.)
void AabbTree::ReinsertMovedLeaves(std::span<const AABB> boxes, detail::WorkerPool* pool) {
  constexpr std::size_t kMinSharedReinserts = 64;
  // Enough for the larger ones to even out: at 4 a thread, 28 and 19 kcyc a step of bench_threads' window
  // on the two threads; at 8, 22 and 21.
  constexpr std::size_t kBranchesPerThread = 8;
  const auto known = static_cast<std::uint32_t>(leaf_of_.size());
  const bool shared = pool && pool->Threads() > 1 && moved_list_.size() >= kMinSharedReinserts &&
                      moved_list_.back() < known;
  if (shared) FindBranches(kBranchesPerThread * static_cast<std::size_t>(pool->Threads()));
  std::span<const std::uint32_t> one_by_one = moved_list_;
  if (shared && !branches_.empty()) {
    SortIntoBranches();
    branch_order_.resize(branches_.size());
    for (std::uint32_t k = 0; k < branch_order_.size(); ++k) branch_order_[k] = k;
    std::stable_sort(branch_order_.begin(), branch_order_.end(), [&](std::uint32_t x, std::uint32_t y) {
      return branch_moved_[x].size() > branch_moved_[y].size();
    });
    const auto count = static_cast<std::uint32_t>(branch_order_.size());
    pool->ParallelRuns(count, 0, 1, [&](std::uint32_t begin, std::uint32_t end) {
      for (std::uint32_t k = begin; k < end; ++k) {
        ReinsertInBranch(boxes, branches_[branch_order_[k]], branch_moved_[branch_order_[k]]);
      }
    });
    for (const Branch& branch : branches_) RefitUpward(branch.parent);
    one_by_one = outside_moved_;
  }
  for (const std::uint32_t i : one_by_one) {
    bool stretched = false;
    if (i >= known) {
      const std::int32_t leaf = Allocate();
      nodes_[leaf].body = i;
      nodes_[leaf].box = FatBox(boxes[i], boxes[i], &stretched);
      InsertLeaf(leaf);
      leaf_of_.push_back(leaf);
      continue;
    }
    const std::int32_t leaf = leaf_of_[i];
    RemoveLeaf(leaf);
    nodes_[leaf].box = FatBox(boxes[i], PreviousBox(boxes, i), &stretched);
    nodes_[leaf].stretched = stretched;
    InsertLeaf(leaf);
  }
}

// Down from the root, the tallest branch is cut into its root's two children until there are
// `count` branches or none is tall enough to cut (a branch's root must have children: a leaf
// that moved goes back from outside). Rotations lift wide boxes, a floor or a wall, to the top,
// so the top is seldom even: cutting the tallest follows the bulk of the leaves.
void AabbTree::FindBranches(std::size_t count) {
  branches_.clear();
  if (root_ == kNull || nodes_[root_].height < 2) return;
  branches_.push_back({root_, 0});
  branches_.push_back({root_, 1});
  while (branches_.size() < count) {
    std::size_t tallest = branches_.size();
    std::int32_t tallest_height = 1;  // only a root of height 2 or more is cut
    for (std::size_t k = 0; k < branches_.size(); ++k) {
      const std::int32_t height = nodes_[BranchRoot(branches_[k])].height;
      if (height > tallest_height) {
        tallest = k;
        tallest_height = height;
      }
    }
    if (tallest == branches_.size()) break;
    const std::int32_t root = BranchRoot(branches_[tallest]);
    branches_[tallest] = {root, 0};
    branches_.push_back({root, 1});
  }
}

// Each moved leaf into the branch above it, in id order, or into outside_moved_: up from the
// leaf to the first branch root (marked in branch_of_node_, which is all -1 between calls).
void AabbTree::SortIntoBranches() {
  branch_of_node_.resize(nodes_.size(), -1);
  for (std::size_t k = 0; k < branches_.size(); ++k) {
    const std::int32_t root = BranchRoot(branches_[k]);
    if (!nodes_[root].IsLeaf()) branch_of_node_[static_cast<std::size_t>(root)] = static_cast<std::int32_t>(k);
  }
  if (branch_moved_.size() < branches_.size()) branch_moved_.resize(branches_.size());
  for (std::size_t k = 0; k < branches_.size(); ++k) branch_moved_[k].clear();
  outside_moved_.clear();
  for (const std::uint32_t i : moved_list_) {
    std::int32_t node = leaf_of_[i];
    while (node != kNull && branch_of_node_[static_cast<std::size_t>(node)] < 0) node = nodes_[node].parent;
    if (node == kNull) {
      outside_moved_.push_back(i);
    } else {
      branch_moved_[static_cast<std::size_t>(branch_of_node_[static_cast<std::size_t>(node)])].push_back(i);
    }
  }
  for (const Branch& branch : branches_) branch_of_node_[static_cast<std::size_t>(BranchRoot(branch))] = -1;
}

// A branch's moved leaves go back into it, in id order: each leaf's old parent node becomes its
// new one, and nothing from the branch's parent up is read or refitted, but for the branch's own
// child link (written without reading its sibling's, which another thread may be writing).
// Branches hold apart nodes, so they go back on several threads at once; a leaf may stay in a
// branch it has left, which costs a looser tree until the next rebuild, never a pair.
void AabbTree::ReinsertInBranch(std::span<const AABB> boxes, const Branch& branch,
                                std::span<const std::uint32_t> moved) {
  for (const std::uint32_t i : moved) {
    const std::int32_t leaf = leaf_of_[i];
    const std::int32_t parent = DetachLeaf(leaf, branch.parent, branch.side);
    bool stretched = false;
    nodes_[leaf].box = FatBox(boxes[i], PreviousBox(boxes, i), &stretched);
    nodes_[leaf].stretched = stretched;
    AttachLeaf(leaf, parent, BranchRoot(branch), branch.parent, branch.side);
  }
}

// Many moved (a quarter or more: a pile in motion, the first call): a new tree over all the fat
// boxes costs less than reinserting them one by one, and comes out balanced and in depth-first
// order. Its shape never shows in the pairs, which are those of overlapping fat boxes.
void AabbTree::Rebuild(std::span<const AABB> boxes, detail::WorkerPool* pool) {
  const auto n = static_cast<std::uint32_t>(boxes.size());
  const auto known = static_cast<std::uint32_t>(leaf_of_.size());
  leaves_.resize(n);
  build_items_.resize(n);
  detail::ForEachIndexInRuns(pool, n, kMinSharedLeaves, [&](std::uint32_t i) {
    Node& leaf = leaves_[i];
    if (i < known && !moved_[i]) {
      leaf = nodes_[leaf_of_[i]];
    } else {
      leaf = Node{};
      leaf.body = i;
      leaf.box = FatBox(boxes[i], i < known ? PreviousBox(boxes, i) : boxes[i], &leaf.stretched);
    }
    build_items_[i] = {leaf.box.lower + leaf.box.upper, i};
  });
  nodes_.assign(n == 0 ? 0 : 2 * std::size_t{n} - 1, Node{});
  leaf_of_.resize(n);
  free_list_ = kNull;
  root_ = n == 0 ? kNull : 0;
  reinserts_since_relayout_ = 0;
  if (n > 0) BuildSubtree(0, n, 0, kNull, n >= kMinSharedLeaves ? pool : nullptr);
}

// The subtree over build_items_[first, last) at node `index`, its first child's subtree right
// after it and the second's after that (a subtree of k leaves takes 2k − 1 nodes). Split at the
// median of the wider axis of the centres, ties by body: the shape depends on the boxes alone.
// With a pool, the two halves are built side by side (they write apart).
void AabbTree::BuildSubtree(std::uint32_t first, std::uint32_t last, std::int32_t index, std::int32_t parent,
                            detail::WorkerPool* pool) {
  Node& node = nodes_[index];
  if (last - first == 1) {
    const std::uint32_t body = build_items_[first].body;
    node = leaves_[body];
    node.parent = parent;
    node.child1 = node.child2 = kNull;
    node.height = 0;
    leaf_of_[body] = index;
    return;
  }
  Vec2 lo = build_items_[first].centre, hi = lo;
  for (std::uint32_t k = first + 1; k < last; ++k) {
    const Vec2 c = build_items_[k].centre;
    lo = {std::min(lo.x, c.x), std::min(lo.y, c.y)};
    hi = {std::max(hi.x, c.x), std::max(hi.y, c.y)};
  }
  const bool along_x = hi.x - lo.x >= hi.y - lo.y;
  const std::uint32_t middle = first + (last - first) / 2;
  std::nth_element(build_items_.begin() + first, build_items_.begin() + middle, build_items_.begin() + last,
                   [along_x](const BuildItem& p, const BuildItem& q) {
                     const double a = along_x ? p.centre.x : p.centre.y, b = along_x ? q.centre.x : q.centre.y;
                     return a < b || (a == b && p.body < q.body);
                   });
  const std::int32_t child1 = index + 1;
  const auto child2 = static_cast<std::int32_t>(index + 2 * (middle - first));
  if (pool) {
    pool->RunSideBySide([&] { BuildSubtree(first, middle, child1, index, nullptr); },
                        [&] { BuildSubtree(middle, last, child2, index, nullptr); });
  } else {
    BuildSubtree(first, middle, child1, index, nullptr);
    BuildSubtree(middle, last, child2, index, nullptr);
  }
  node.parent = parent;
  node.child1 = child1;
  node.child2 = child2;
  node.box = Union(nodes_[child1].box, nodes_[child2].box);
  node.height = 1 + std::max(nodes_[child1].height, nodes_[child2].height);
}

// The candidates are the pairs whose fat boxes overlap. Only a moved leaf's fat box changed, so
// only its pairs need finding again; when many moved, one traversal of the whole tree is cheaper.
bool AabbTree::RefreshCandidates(std::span<const AABB> boxes, detail::WorkerPool* pool) {
  const std::size_t n = boxes.size();
  // A crowded tree kept no candidates, and an update that would outgrow the limit gives way to
  // a whole traversal, which finds out whether the tree is still crowded.
  if (!crowded_ && 4 * moved_list_.size() <= n && !moved_list_.empty() && UpdateCandidates(boxes, pool)) return true;
  if (crowded_ || !moved_list_.empty()) FindAllCandidates(boxes, pool);
  return false;
}

// Shared, the threads check runs of the candidates, each run taken by whichever thread is free
// (the candidates were merged on thread 0: the other reads them cold), and keep the overlapping
// ones; the runs then go to the collector in order, as one thread's would.
void AabbTree::AddOverlappingCandidates(std::span<const AABB> boxes, detail::WorkerPool* pool) {
  const int threads = pool ? pool->Threads() : 1;
  if (threads == 1 || candidates_.size() < kMinSharedCandidates) {
    found_.resize(1);
    FoundRun& found = found_[0].value;
    found.count = OverlappingInto(candidates_, boxes, &found.pairs);
    for (std::size_t k = 0; k < found.count; ++k) collector_.Add(found.pairs[k].a, found.pairs[k].b);
    return;
  }
  const auto n = static_cast<std::uint32_t>(candidates_.size());
  const std::uint32_t run = detail::RunLength(pool, n, kMinSharedCandidates);
  found_.resize((n + run - 1) / run);
  pool->ParallelRuns(n, 0, run, [&](std::uint32_t begin, std::uint32_t end) {
    FoundRun& found = found_[begin / run].value;
    found.count = OverlappingInto(std::span<const BodyPair>(candidates_).subspan(begin, end - begin), boxes,
                                  &found.pairs);
  });
  CollectFound(pool);
}

void AabbTree::CollectFound(detail::WorkerPool* pool) {
  found_runs_.clear();
  for (const auto& part : found_) found_runs_.emplace_back(part.value.pairs.data(), part.value.count);
  collector_.AddRuns(found_runs_, pool);
}

std::size_t AabbTree::CandidateLimit() const { return kCandidatesPerBody * leaf_of_.size() + 1024; }

// One step of the tree's traversal against itself: the node pair (a, b), a node with itself or
// two whose boxes overlap, hands on its children's pairs that overlap, or is a candidate when both
// are leaves. Each subtree is met against itself and the two children of every node against each
// other, descending only where fat boxes overlap.
template <typename Push, typename Found>
void AabbTree::VisitNodePair(std::int32_t a, std::int32_t b, Push&& push, Found&& found) const {
  const Node& na = nodes_[a];
  auto push_if_overlapping = [&](std::int32_t p, std::int32_t q) {
    if (Overlaps(nodes_[p].box, nodes_[q].box)) push(p, q);
  };
  if (a == b) {
    if (na.IsLeaf()) return;
    push(na.child1, na.child1);
    push(na.child2, na.child2);
    push_if_overlapping(na.child1, na.child2);
    return;
  }
  const Node& nb = nodes_[b];
  if (na.IsLeaf() && nb.IsLeaf()) {
    found(na.body, nb.body);
    return;
  }
  // Split the bigger side, so the two stay of similar size as they descend.
  if (nb.IsLeaf() || (!na.IsLeaf() && Perimeter(na.box) >= Perimeter(nb.box))) {
    push_if_overlapping(na.child1, b);
    push_if_overlapping(na.child2, b);
  } else {
    push_if_overlapping(a, nb.child1);
    push_if_overlapping(a, nb.child2);
  }
}

void AabbTree::FindAllCandidates(std::span<const AABB> boxes, detail::WorkerPool* pool) {
  // Candidates beyond the limit (bodies piled up) are not kept: every overlapping pair goes to
  // the collector instead, which bounds them. A tree crowded last call is traversed on one thread.
  const bool was_crowded = crowded_;
  crowded_ = false;
  if (!was_crowded && pool && pool->Threads() > 1 && leaf_of_.size() >= kMinSharedLeaves &&
      FindAllCandidatesShared(*pool)) {
    detail::SortPairs(leaf_of_.size(), &candidates_, &sorted_scratch_, &counts_);
    return;
  }
  candidates_.clear();
  const std::size_t limit = CandidateLimit();
  stack_.clear();
  if (root_ != kNull) stack_.push_back({root_, root_});
  while (!stack_.empty()) {
    const auto [a, b] = stack_.back();
    stack_.pop_back();
    VisitNodePair(
        a, b, [this](std::int32_t p, std::int32_t q) { stack_.push_back({p, q}); },
        [&](std::uint32_t p, std::uint32_t q) { AddCandidate(p, q, boxes, limit); });
  }
  if (!crowded_) detail::SortPairs(leaf_of_.size(), &candidates_, &sorted_scratch_, &counts_);
}

// The traversal is split level by level from the root's pair with itself until there are node
// pairs enough for every thread to take several, each with its own list, whichever thread is free.
// False, with the lists together past the candidate limit: the tree is crowded, and the caller
// traverses it alone, the way that bounds what the pairs cost.
bool AabbTree::FindAllCandidatesShared(detail::WorkerPool& pool) {
  constexpr std::size_t kNodePairsPerThread = 16;
  const std::size_t limit = CandidateLimit();
  const std::size_t enough = kNodePairsPerThread * static_cast<std::size_t>(pool.Threads());
  const auto found = [this](std::uint32_t p, std::uint32_t q) { candidates_.push_back(MakePair(p, q)); };
  candidates_.clear();
  node_pairs_.assign(1, {root_, root_});
  while (!node_pairs_.empty() && node_pairs_.size() < enough) {
    stack_.clear();
    for (const auto& [a, b] : node_pairs_) {
      VisitNodePair(a, b, [this](std::int32_t p, std::int32_t q) { stack_.push_back({p, q}); }, found);
    }
    node_pairs_.swap(stack_);
  }
  const auto count = static_cast<std::uint32_t>(node_pairs_.size());
  traversal_runs_.resize(count);
  pool.ParallelRuns(count, 0, 1, [&](std::uint32_t begin, std::uint32_t end) {
    TraversalRun& run = traversal_runs_[begin].value;
    run.pairs.clear();
    for (std::uint32_t k = begin; k < end; ++k) {
      run.stack.assign(1, node_pairs_[k]);
      while (!run.stack.empty() && run.pairs.size() <= limit) {
        const auto [a, b] = run.stack.back();
        run.stack.pop_back();
        VisitNodePair(
            a, b, [&run](std::int32_t p, std::int32_t q) { run.stack.push_back({p, q}); },
            [&run](std::uint32_t p, std::uint32_t q) { run.pairs.push_back(MakePair(p, q)); });
      }
    }
  });
  std::size_t total = candidates_.size();
  for (const auto& run : traversal_runs_) total += run.value.pairs.size();
  if (total > limit) return false;
  for (const auto& run : traversal_runs_) {
    candidates_.insert(candidates_.end(), run.value.pairs.begin(), run.value.pairs.end());
  }
  return true;
}

// Past the limit the tree is crowded: the pairs kept so far and all that follow go straight to the
// collector, which bounds them.
void AabbTree::AddCandidate(std::uint32_t a, std::uint32_t b, std::span<const AABB> boxes, std::size_t limit) {
  if (crowded_) {
    if (Overlaps(boxes[a], boxes[b])) collector_.Add(a, b);
    return;
  }
  candidates_.push_back(MakePair(a, b));
  if (candidates_.size() <= limit) return;
  crowded_ = true;
  AddOverlappingCandidates(boxes, nullptr);
  candidates_.clear();
  candidates_.shrink_to_fit();
}

// Each moved body's new pairs from a query of the tree (a pair of two moved bodies is taken from
// the smaller id only): the queries only read the tree, so shared, each thread queries a run of
// the moved bodies and sorts what it found. Then, in runs of last call's candidates, each run
// drops its pairs with a moved body, merges in the fresh pairs that sort within its stretch and
// tests the bodies' own boxes of what it keeps (into found_): the runs, joined in order, are the
// sorted candidates and the overlapping ones, as one thread would find them.
bool AabbTree::UpdateCandidates(std::span<const AABB> boxes, detail::WorkerPool* pool) {
  constexpr std::size_t kMinSharedQueries = 64;
  const std::size_t limit = CandidateLimit();
  const int threads = pool && moved_list_.size() >= kMinSharedQueries ? pool->Threads() : 1;
  fresh_runs_.resize(static_cast<std::size_t>(threads));
  const auto query_run = [&](int t) {
    const std::size_t n = moved_list_.size();
    const auto part = static_cast<std::size_t>(t), parts = static_cast<std::size_t>(threads);
    FreshRun& run = fresh_runs_[part].value;
    run.pairs.clear();
    for (std::size_t k = n * part / parts; k < n * (part + 1) / parts && run.pairs.size() <= limit; ++k) {
      QueryFreshPairs(moved_list_[k], &run.stack, &run.pairs);
    }
    // The linear counting sort once the pairs pay for its counts over all the bodies, std::sort
    // below: its comparisons mispredict (in bench_threads' window of the 4 000-circle pour, 80
    // kcyc for 1 100 pairs against 12; 1.4 against 8.6 for fewer than 64).
    if (run.pairs.size() * kBodiesPerCountedPair >= leaf_of_.size()) {
      detail::SortPairs(leaf_of_.size(), &run.pairs, &run.sorted_scratch, &run.counts);
    } else {
      std::sort(run.pairs.begin(), run.pairs.end());
    }
  };
  if (threads == 1) {
    query_run(0);
  } else {
    pool->RunOnAll(query_run);
  }
  fresh_.clear();
  for (const auto& run : fresh_runs_) {
    const auto middle = static_cast<std::ptrdiff_t>(fresh_.size());
    fresh_.insert(fresh_.end(), run.value.pairs.begin(), run.value.pairs.end());
    std::inplace_merge(fresh_.begin(), fresh_.begin() + middle, fresh_.end());
  }
  if (fresh_.size() > limit) return false;

  const auto n = static_cast<std::uint32_t>(candidates_.size());
  const std::uint32_t count = std::max<std::uint32_t>(n, 1);  // a run even with no candidates: the fresh pairs
  const std::uint32_t run = detail::RunLength(pool, count, kMinSharedCandidates);
  const std::size_t runs = (count + run - 1) / run;
  found_.resize(runs);
  merged_.resize(runs);
  const auto fresh_from = [&](std::uint32_t i) {
    if (i == 0) return fresh_.cbegin();
    return i >= n ? fresh_.cend() : std::lower_bound(fresh_.cbegin(), fresh_.cend(), candidates_[i]);
  };
  const auto merge_run = [&](std::uint32_t begin, std::uint32_t end) {
    std::vector<BodyPair>& merged = merged_[begin / run].value;
    FoundRun& found = found_[begin / run].value;
    merged.clear();
    auto fresh = fresh_from(begin);
    const auto fresh_end = end >= count ? fresh_.cend() : fresh_from(end);
    // Kept: at most the run's candidates and its fresh pairs; the overlapping ones as in
    // OverlappingInto, without a branch.
    const std::size_t most = (std::min(end, n) - begin) + static_cast<std::size_t>(fresh_end - fresh);
    if (found.pairs.size() < most) found.pairs.resize(most);
    BodyPair* overlapping = found.pairs.data();
    std::size_t overlaps = 0;
    const auto keep = [&](BodyPair p) {
      merged.push_back(p);
      overlapping[overlaps] = p;
      overlaps += OverlapsJoined(boxes[p.a], boxes[p.b]) ? 1 : 0;
    };
    for (std::uint32_t i = begin; i < std::min(end, n); ++i) {
      const BodyPair p = candidates_[i];
      if (moved_[p.a] || moved_[p.b]) continue;
      for (; fresh != fresh_end && *fresh < p; ++fresh) keep(*fresh);
      keep(p);
    }
    for (; fresh != fresh_end; ++fresh) keep(*fresh);
    found.count = overlaps;
  };
  detail::ForEachRun(pool, count, kMinSharedCandidates, run, merge_run);
  std::size_t total = 0;
  for (const auto& part : merged_) total += part.value.size();
  if (total > limit) return false;
  candidates_.clear();
  for (const auto& part : merged_) candidates_.insert(candidates_.end(), part.value.begin(), part.value.end());
  return true;
}

void AabbTree::QueryFreshPairs(std::uint32_t body, std::vector<std::int32_t>* stack,
                               std::vector<BodyPair>* fresh) const {
  const AABB& box = nodes_[leaf_of_[body]].box;
  stack->clear();
  stack->push_back(root_);
  while (!stack->empty()) {
    const Node& node = nodes_[stack->back()];
    stack->pop_back();
    if (!Overlaps(node.box, box)) continue;
    if (!node.IsLeaf()) {
      stack->push_back(node.child1);
      stack->push_back(node.child2);
      continue;
    }
    const std::uint32_t other = node.body;
    if (other != body && (!moved_[other] || body < other)) fresh->push_back(MakePair(body, other));
  }
}

// Insertions scatter new nodes over the array, and the traversal below jumps between them; in
// depth-first order the nodes it visits together lie together.
void AabbTree::Relayout() {
  if (root_ == kNull) return;
  relayout_scratch_.clear();
  new_index_.assign(nodes_.size(), kNull);
  // Preorder numbering with an explicit stack: child1's subtree first.
  stack_.clear();
  stack_.push_back({root_, kNull});
  while (!stack_.empty()) {
    const auto [old_index, new_parent] = stack_.back();
    stack_.pop_back();
    const auto index = static_cast<std::int32_t>(relayout_scratch_.size());
    new_index_[old_index] = index;
    Node node = nodes_[old_index];
    node.parent = new_parent;
    relayout_scratch_.push_back(node);
    if (new_parent != kNull) {
      Node& parent = relayout_scratch_[new_parent];
      (parent.child1 == old_index ? parent.child1 : parent.child2) = index;
    }
    if (!node.IsLeaf()) {
      stack_.push_back({node.child2, index});
      stack_.push_back({node.child1, index});
    }
  }
  for (std::int32_t& leaf : leaf_of_) leaf = new_index_[leaf];
  nodes_.swap(relayout_scratch_);
  root_ = 0;
  free_list_ = kNull;
}

int AabbTree::Height() const { return root_ == kNull ? -1 : nodes_[root_].height; }

bool AabbTree::IsValid() const {
  if (root_ == kNull) return leaf_of_.empty();
  if (nodes_[root_].parent != kNull) return false;
  std::size_t leaves = 0;
  std::vector<std::int32_t> todo{root_};
  while (!todo.empty()) {
    const std::int32_t index = todo.back();
    todo.pop_back();
    const Node& node = nodes_[index];
    if (node.IsLeaf()) {
      if (node.height != 0 || node.body >= leaf_of_.size() || leaf_of_[node.body] != index) return false;
      ++leaves;
      continue;
    }
    const Node& c1 = nodes_[node.child1];
    const Node& c2 = nodes_[node.child2];
    if (c1.parent != index || c2.parent != index) return false;
    if (node.height != 1 + std::max(c1.height, c2.height)) return false;
    if (!SameBox(node.box, Union(c1.box, c2.box))) return false;
    todo.push_back(node.child1);
    todo.push_back(node.child2);
  }
  return leaves == leaf_of_.size();
}

}  // namespace engine
