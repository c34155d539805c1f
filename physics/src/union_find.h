#pragma once
// Union-find over a parent array indexed by an id type (the parting's groups of bodies, the
// islands' nodes): find with path halving, and union that keeps the smaller id as the root, so
// that a group's root does not depend on the order of the joins.
#include <algorithm>
#include <vector>

namespace phys::detail {

template <typename IdT>
IdT findRoot(std::vector<IdT>& parent, IdT id) {
  while (parent[id] != id) {
    parent[id] = parent[parent[id]];  // path halving
    id = parent[id];
  }
  return id;
}

template <typename IdT>
void unite(std::vector<IdT>& parent, IdT a, IdT b) {
  const IdT ra = findRoot(parent, a), rb = findRoot(parent, b);
  if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
}

}  // namespace phys::detail
