#include "joint_forest.h"

#include <algorithm>
#include <array>
#include <deque>
#include <map>
#include <utility>

#include <glm/geometric.hpp>

namespace lab::peers {
namespace {

// Pins closer than this are one point; a pin whose ends start farther apart is not shut. Ours
// start shut to round-off (1e-15 m); a micrometre leaves room for a file's printed digits.
constexpr double kSamePoint = 1e-6;  // unit: m

// The joint that the shut pins between two bodies make, at their points (world, at the start).
TreeNode jointOf(const std::vector<phys::Vec3>& points) {
  std::vector<phys::Vec3> distinct;
  for (const phys::Vec3& p : points) {
    if (std::none_of(distinct.begin(), distinct.end(),
                     [&](const phys::Vec3& q) { return glm::length(p - q) <= kSamePoint; })) {
      distinct.push_back(p);
    }
  }
  TreeNode node;
  node.anchor = distinct.front();
  if (distinct.size() == 1) {
    node.joint = TreeJoint::Ball;
    return node;
  }
  // The line through the two points farthest apart; a hinge if every point lies on it.
  std::size_t i = 0, j = 1;
  for (std::size_t a = 0; a < distinct.size(); ++a) {
    for (std::size_t b = a + 1; b < distinct.size(); ++b) {
      if (glm::length(distinct[a] - distinct[b]) > glm::length(distinct[i] - distinct[j])) i = a, j = b;
    }
  }
  const phys::Vec3 axis = glm::normalize(distinct[j] - distinct[i]);
  const bool onLine = std::all_of(distinct.begin(), distinct.end(), [&](const phys::Vec3& p) {
    const phys::Vec3 r = p - distinct[i];
    return glm::length(r - axis * glm::dot(r, axis)) <= kSamePoint;
  });
  node.joint = onLine ? TreeJoint::Hinge : TreeJoint::Weld;
  node.anchor = distinct[i];
  node.axis = axis;
  return node;
}

}  // namespace

JointForest jointForest(const Description& scene, bool tree) {
  const std::size_t n = scene.bodies.size();
  JointForest f;
  f.nodes.assign(n, TreeNode{});
  f.children.assign(n, {});
  f.pinInTree.assign(scene.pins.size(), false);

  // The pins of each pair of bodies, if every one of them starts shut; a pair with a pin that
  // starts apart is left to constraints (a joint would close it at once).
  std::map<std::pair<int, int>, std::vector<std::size_t>> pairs;
  std::map<std::pair<int, int>, bool> shut;
  for (std::size_t k = 0; k < scene.pins.size(); ++k) {
    const Pin& p = scene.pins[k];
    const auto key = std::minmax(p.a, p.b);
    pairs[key].push_back(k);
    const bool closed = glm::length(p.worldB - p.worldA) <= kSamePoint;
    shut[key] = shut.count(key) == 0 ? closed : shut[key] && closed;
  }
  std::vector<std::vector<int>> neighbours(n);
  if (tree) {
    for (const auto& [key, pins] : pairs) {
      if (!shut[key]) continue;
      neighbours[static_cast<std::size_t>(key.first)].push_back(key.second);
      neighbours[static_cast<std::size_t>(key.second)].push_back(key.first);
    }
  }

  // Breadth first from each root: fixed bodies first (a fixed body must be a root: as a child it
  // would move), then each movable body not reached yet. A fixed body is never entered.
  std::vector<bool> reached(n, false);
  auto grow = [&](int root) {
    std::deque<int> queue{root};
    reached[static_cast<std::size_t>(root)] = true;
    while (!queue.empty()) {
      const int body = queue.front();
      queue.pop_front();
      for (const int next : neighbours[static_cast<std::size_t>(body)]) {
        const auto k = static_cast<std::size_t>(next);
        if (reached[k] || scene.bodies[k].fixed) continue;
        reached[k] = true;
        const std::vector<std::size_t>& pins = pairs[std::minmax(body, next)];
        std::vector<phys::Vec3> points;
        for (const std::size_t p : pins) {
          points.push_back(scene.pins[p].worldA);
          f.pinInTree[p] = true;
        }
        f.nodes[k] = jointOf(points);
        f.nodes[k].parent = body;
        f.children[static_cast<std::size_t>(body)].push_back(next);
        queue.push_back(next);
      }
    }
  };
  for (const bool fixedRoots : {true, false}) {
    for (std::size_t i = 0; i < n; ++i) {
      if (fixedRoots ? !scene.bodies[i].fixed : reached[i]) continue;
      f.nodes[i].joint = fixedRoots ? TreeJoint::Fixed : TreeJoint::Free;
      f.roots.push_back(static_cast<int>(i));
      grow(static_cast<int>(i));
    }
  }
  std::sort(f.roots.begin(), f.roots.end());
  for (auto& c : f.children) std::sort(c.begin(), c.end());
  // The coordinates each joint adds, in TreeJoint's order: free, fixed, ball, hinge, weld. at():
  // a value cast from outside the enum throws.
  constexpr std::array<int, 5> kDofs{6, 0, 3, 1, 0};
  for (const TreeNode& node : f.nodes) f.dofs += kDofs.at(static_cast<std::size_t>(node.joint));
  return f;
}

}  // namespace lab::peers
