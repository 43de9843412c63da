// The dynamic AABB tree broad phase: a leaf per body with a fattened box, reinserted only when the
// body leaves it; pairs from one traversal of the tree against itself.
//
// The ideas follow Erin Catto's b2DynamicTree (Box2D 2.x; "Dynamic Bounding Volume Hierarchies",
// GDC 2019): insertion descends by a surface-area (here perimeter) cost with branch and bound,
// ancestors are refitted on the way up and rotated when one child is two levels taller.
#include <algorithm>
#include <cmath>

#include "engine/broadphase.h"
#include "pair_sort.h"

namespace engine {

namespace {

// A leaf's box is the body's grown by this fraction of its larger side, so that small motions
// (a pile settling, a contact jittering) stay inside it and cost nothing.
constexpr double kMarginFraction = 0.1;
// And stretched this many times the body's last displacement ahead of it, so that a steadily
// moving body (a falling one) is reinserted every few steps rather than every step. The stretch
// is capped at the body's size so that a teleport does not leave a long box behind.
constexpr double kPredictSteps = 2.0;

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

AABB AabbTree::FatBox(const AABB& box, const AABB& previous) const {
  const double size = std::max(box.upper.x - box.lower.x, box.upper.y - box.lower.y);
  const double margin = kMarginFraction * size;
  AABB fat{box.lower - Vec2{margin, margin}, box.upper + Vec2{margin, margin}};
  const Vec2 moved = 0.5 * (box.lower + box.upper) - 0.5 * (previous.lower + previous.upper);
  const double dx = Clamp(kPredictSteps * moved.x, -size, size);
  const double dy = Clamp(kPredictSteps * moved.y, -size, size);
  (dx < 0.0 ? fat.lower.x : fat.upper.x) += dx;
  (dy < 0.0 ? fat.lower.y : fat.upper.y) += dy;
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
}

void AabbTree::InsertLeaf(std::int32_t leaf) {
  if (root_ == kNull) {
    root_ = leaf;
    nodes_[leaf].parent = kNull;
    return;
  }
  // Find the sibling whose pairing with the leaf adds the least perimeter over the whole tree:
  // stop at a node when making it the sibling is cheaper than the best each child could offer
  // (every ancestor on the way grows by `inheritance` either way).
  const AABB box = nodes_[leaf].box;
  std::int32_t index = root_;
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

  const std::int32_t sibling = index;
  const std::int32_t old_parent = nodes_[sibling].parent;
  const std::int32_t parent = Allocate();
  Node& p = nodes_[parent];
  p.parent = old_parent;
  p.box = Union(box, nodes_[sibling].box);
  p.height = nodes_[sibling].height + 1;
  p.child1 = sibling;
  p.child2 = leaf;
  nodes_[sibling].parent = parent;
  nodes_[leaf].parent = parent;
  if (old_parent == kNull) {
    root_ = parent;
  } else if (nodes_[old_parent].child1 == sibling) {
    nodes_[old_parent].child1 = parent;
  } else {
    nodes_[old_parent].child2 = parent;
  }
  RefitUpward(parent);  // the new parent too: its sibling side may be two or more levels taller
}

void AabbTree::RemoveLeaf(std::int32_t leaf) {
  if (leaf == root_) {
    root_ = kNull;
    return;
  }
  const std::int32_t parent = nodes_[leaf].parent;
  const std::int32_t grandparent = nodes_[parent].parent;
  const std::int32_t sibling = nodes_[parent].child1 == leaf ? nodes_[parent].child2 : nodes_[parent].child1;
  Free(parent);
  nodes_[sibling].parent = grandparent;
  if (grandparent == kNull) {
    root_ = sibling;
    return;
  }
  if (nodes_[grandparent].child1 == parent) {
    nodes_[grandparent].child1 = sibling;
  } else {
    nodes_[grandparent].child2 = sibling;
  }
  RefitUpward(grandparent);
}

void AabbTree::RefitUpward(std::int32_t node) {
  while (node != kNull) {
    node = Balance(node);
    Node& n = nodes_[node];
    const Node& c1 = nodes_[n.child1];
    const Node& c2 = nodes_[n.child2];
    n.height = 1 + std::max(c1.height, c2.height);
    n.box = Union(c1.box, c2.box);
    node = n.parent;
  }
}

// When one child of `a` is two or more levels taller, that child rises into a's place with a as
// its child, and its shorter child moves down under a in the slot it left: the two sides end
// nearer in height (an AVL single rotation). Returns the node now in a's place.
std::int32_t AabbTree::Balance(std::int32_t a) {
  Node& node_a = nodes_[a];
  if (node_a.IsLeaf()) return a;
  const std::int32_t b = node_a.child1;
  const std::int32_t c = node_a.child2;
  const std::int32_t balance = nodes_[c].height - nodes_[b].height;
  if (balance >= -1 && balance <= 1) return a;

  // `up` is the taller child, `stay` the other one.
  const std::int32_t up = balance > 1 ? c : b;
  const std::int32_t stay = balance > 1 ? b : c;
  Node& node_up = nodes_[up];
  const std::int32_t f = node_up.child1;
  const std::int32_t g = node_up.child2;
  // The taller grandchild stays under `up`; the shorter one moves under a in up's old slot.
  const bool f_taller = nodes_[f].height > nodes_[g].height;
  const std::int32_t keep = f_taller ? f : g;
  const std::int32_t move = f_taller ? g : f;

  node_up.parent = node_a.parent;
  if (node_up.parent == kNull) {
    root_ = up;
  } else if (nodes_[node_up.parent].child1 == a) {
    nodes_[node_up.parent].child1 = up;
  } else {
    nodes_[node_up.parent].child2 = up;
  }
  node_up.child1 = a;
  node_up.child2 = keep;
  node_a.parent = up;
  if (balance > 1) {
    node_a.child2 = move;
  } else {
    node_a.child1 = move;
  }
  nodes_[move].parent = a;

  node_a.box = Union(nodes_[stay].box, nodes_[move].box);
  node_a.height = 1 + std::max(nodes_[stay].height, nodes_[move].height);
  node_up.box = Union(node_a.box, nodes_[keep].box);
  node_up.height = 1 + std::max(node_a.height, nodes_[keep].height);
  return up;
}

void AabbTree::FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs) {
  pairs->clear();
  const std::size_t n = boxes.size();
  if (n < leaf_of_.size()) Clear();  // bodies went away: start over

  // Bodies that left their fat box, then new bodies, each in id order.
  last_reinserts_ = 0;
  const std::size_t known = leaf_of_.size();
  for (std::uint32_t i = 0; i < known; ++i) {
    const std::int32_t leaf = leaf_of_[i];
    if (Contains(nodes_[leaf].box, boxes[i])) continue;
    RemoveLeaf(leaf);
    nodes_[leaf].box = FatBox(boxes[i], previous_[i]);
    InsertLeaf(leaf);
    ++last_reinserts_;
  }
  for (std::uint32_t i = static_cast<std::uint32_t>(known); i < n; ++i) {
    const std::int32_t leaf = Allocate();
    nodes_[leaf].body = i;
    nodes_[leaf].box = FatBox(boxes[i], boxes[i]);
    InsertLeaf(leaf);
    leaf_of_.push_back(leaf);
    ++last_reinserts_;
  }
  previous_.assign(boxes.begin(), boxes.end());

  // The tree against itself: each subtree against itself, and the two children of every node
  // against each other, descending only where fat boxes overlap; the bodies' own boxes decide.
  stack_.clear();
  if (root_ != kNull) stack_.push_back({root_, root_});
  while (!stack_.empty()) {
    const auto [a, b] = stack_.back();
    stack_.pop_back();
    const Node& na = nodes_[a];
    if (a == b) {
      if (na.IsLeaf()) continue;
      stack_.push_back({na.child1, na.child1});
      stack_.push_back({na.child2, na.child2});
      stack_.push_back({na.child1, na.child2});
      continue;
    }
    const Node& nb = nodes_[b];
    if (!Overlaps(na.box, nb.box)) continue;
    if (na.IsLeaf() && nb.IsLeaf()) {
      if (Overlaps(boxes[na.body], boxes[nb.body])) pairs->push_back(detail::MakePair(na.body, nb.body));
      continue;
    }
    // Split the bigger side, so the two stay of similar size as they descend.
    if (nb.IsLeaf() || (!na.IsLeaf() && Perimeter(na.box) >= Perimeter(nb.box))) {
      stack_.push_back({na.child1, b});
      stack_.push_back({na.child2, b});
    } else {
      stack_.push_back({a, nb.child1});
      stack_.push_back({a, nb.child2});
    }
  }
  detail::SortPairs(n, pairs, &sorted_scratch_, &counts_);
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
