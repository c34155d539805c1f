#include "mujoco_model.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "joint_forest.h"
#include "text.h"

namespace lab::peers::mjcf {
namespace {

// Every digit a double has, so MuJoCo reads back the very number.
std::string num(double v) {
  return formatNumber(v, 17);
}
std::string vec(const phys::Vec3& v) {
  return num(v.x) + " " + num(v.y) + " " + num(v.z);
}
std::string quat(const phys::Quat& q) {
  return num(q.w) + " " + num(q.x) + " " + num(q.y) + " " + num(q.z);
}
std::string friction(double mu) {
  return num(mu) + " 0.005 0.0001";
}  // MuJoCo's torsional and rolling defaults
std::string name(char kind, std::size_t i) {
  return std::string(1, kind) + std::to_string(i);
}

// A solid's geom type and size. MuJoCo's capsule lies along its geom's z; `fromto` puts its core
// on the body's y instead, so the body frame stays ours. A capsule without a core (a sphere,
// which fromto cannot say) is a sphere geom.
std::string shapeOf(const Body& b) {
  if (b.shape == Body::Shape::Box) return "type=\"box\" size=\"" + vec(b.halfExtents) + "\"";
  if (b.halfSegment <= 0.0) return "type=\"sphere\" size=\"" + num(b.radius) + "\"";
  return "type=\"capsule\" size=\"" + num(b.radius) + "\" fromto=\"0 " + num(-b.halfSegment) + " 0 0 " +
         num(b.halfSegment) + " 0\"";
}

// Writes body i and, nested in it, its children: each pose relative to its parent's (the world's
// for a root), its joint at its point in its own frame.
class BodyWriter {
 public:
  BodyWriter(const Description& scene, const JointForest& forest, std::string& out)
      : scene_(scene), forest_(forest), x_(out) {
    sites_.resize(scene.bodies.size());
    for (std::size_t k = 0; k < scene.distances.size(); ++k) {
      const Distance& d = scene.distances[k];
      sites_[static_cast<std::size_t>(d.a)].emplace_back(2 * k, d.localA);
      sites_[static_cast<std::size_t>(d.b)].emplace_back(2 * k + 1, d.localB);
    }
  }

  void write(int index, int depth) {
    const auto i = static_cast<std::size_t>(index);
    const Body& b = scene_.bodies[i];
    const TreeNode& node = forest_.nodes[i];
    const std::string pad(static_cast<std::size_t>(4 + 2 * depth), ' ');
    phys::Vec3 pos = b.centre;
    phys::Quat q = b.orientation;
    if (node.parent >= 0) {
      const Body& parent = scene_.bodies[static_cast<std::size_t>(node.parent)];
      const phys::Quat toParent = glm::inverse(parent.orientation);
      pos = toParent * (b.centre - parent.centre);
      q = toParent * b.orientation;
    }
    x_ += pad + "<body name=\"" + name('b', i) + "\" pos=\"" + vec(pos) + "\" quat=\"" + quat(q) + "\">\n";
    const phys::Quat toLocal = glm::inverse(b.orientation);
    if (node.joint == TreeJoint::Free) x_ += pad + "  <freejoint/>\n";
    if (node.joint == TreeJoint::Ball)
      x_ += pad + "  <joint type=\"ball\" pos=\"" + vec(toLocal * (node.anchor - b.centre)) + "\"/>\n";
    if (node.joint == TreeJoint::Hinge) {
      x_ += pad + "  <joint type=\"hinge\" pos=\"" + vec(toLocal * (node.anchor - b.centre)) + "\" axis=\"" +
            vec(toLocal * node.axis) + "\"/>\n";
    }
    if (!b.fixed)
      x_ += pad + "  <inertial pos=\"0 0 0\" mass=\"" + num(b.mass) + "\" diaginertia=\"" + vec(b.inertia) +
            "\"/>\n";
    if (b.solid()) {
      x_ += pad + "  <geom name=\"" + name('g', i) + "\" " + shapeOf(b) + " friction=\"" +
            friction(b.friction) + "\" contype=\"1\" conaffinity=\"1\"/>\n";
    } else {
      x_ += pad + "  <geom name=\"" + name('g', i) + "\" type=\"sphere\" size=\"" + num(b.radius) +
            "\" contype=\"0\" conaffinity=\"0\"/>\n";
    }
    for (const auto& [site, local] : sites_[i])
      x_ += pad + "  <site name=\"" + name('s', site) + "\" pos=\"" + vec(local) + "\"/>\n";
    for (const int child : forest_.children[i]) write(child, depth + 1);
    x_ += pad + "</body>\n";
  }

 private:
  const Description& scene_;
  const JointForest& forest_;
  std::string& x_;
  std::vector<std::vector<std::pair<std::size_t, phys::Vec3>>> sites_;  // per body: the tendons' ends on it
};

// Ground pairs with our friction, and the pairs our filter keeps apart excluded one by one:
// MuJoCo's contype/conaffinity test is an OR of two ANDs, ours (group against mask both ways)
// an AND.
void writeContacts(const Description& scene, std::string& x) {
  x += "  <contact>\n";
  if (scene.ground) {
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const Body& b = scene.bodies[i];
      if (b.fixed) continue;
      const double mu = std::sqrt(b.friction * scene.groundFriction);
      x += "    <pair geom1=\"ground\" geom2=\"" + name('g', i) + "\" condim=\"3\" friction=\"" + num(mu) +
           " " + num(mu) + " 0.005 0.0001 0.0001\"/>\n";
    }
  }
  std::vector<std::pair<int, int>> excluded = scene.ignored;
  if (!scene.defaultFiltering) {
    excluded.clear();
    const int n = static_cast<int>(scene.bodies.size());
    for (int i = 0; i < n; ++i) {
      if (!scene.bodies[static_cast<std::size_t>(i)].solid()) continue;
      for (int j = i + 1; j < n; ++j) {
        if (scene.bodies[static_cast<std::size_t>(j)].solid() && !scene.collides(i, j))
          excluded.emplace_back(i, j);
      }
    }
  }
  for (const auto& [a, b] : excluded) {
    x += "    <exclude body1=\"" + name('b', static_cast<std::size_t>(a)) + "\" body2=\"" +
         name('b', static_cast<std::size_t>(b)) + "\"/>\n";
  }
  x += "  </contact>\n";
}

void writeTendons(const Description& scene, std::string& x) {
  if (scene.distances.empty()) return;
  x += "  <tendon>\n";
  for (std::size_t k = 0; k < scene.distances.size(); ++k) {
    const Distance& d = scene.distances[k];
    x += "    <spatial name=\"" + name('t', k) + "\"";
    // A one-sided range has no upper bound; MuJoCo wants a number.
    if (!d.rigid())
      x += " limited=\"true\" range=\"" + num(d.min) + " " + num(std::isfinite(d.max) ? d.max : 1e10) + "\"";
    x +=
        "><site site=\"" + name('s', 2 * k) + "\"/><site site=\"" + name('s', 2 * k + 1) + "\"/></spatial>\n";
  }
  x += "  </tendon>\n";
}

}  // namespace

Model writeModel(const Description& scene, double dt, bool tree) {
  Model model;
  model.tree = tree;
  const JointForest forest = jointForest(scene, tree);
  model.dofs = forest.dofs;
  // Up to 8 points for a box on a box and 4 on the ground; a capsule meets the ground and each
  // body it touches at one or two.
  const auto count = [&](auto pred) {
    return static_cast<int>(std::count_if(scene.bodies.begin(), scene.bodies.end(), pred));
  };
  const int capsules = count([](const Body& b) { return b.shape == Body::Shape::Capsule; });
  model.movable = count([](const Body& b) { return !b.fixed; });
  model.contacts =
      10 * (scene.solidCount() - capsules) + 4 * capsules + 2 * static_cast<int>(scene.bodies.size()) + 20;
  for (const Distance& d : scene.distances) (d.rigid() ? model.equalityRows : model.limitRows) += 1;

  std::string x = "<mujoco model=\"peer\">\n";
  x += "  <option timestep=\"" + num(dt) + "\" gravity=\"" + vec(scene.gravity) + "\">\n";
  // MuJoCo keeps a child from touching its parent; ours lets them touch unless told not to
  // (the ignored pairs, excluded below).
  if (tree) x += "    <flag filterparent=\"disable\"/>\n";
  x += "  </option>\n";
  x += "  <size njmax=\"1\" nconmax=\"1\"/>\n";
  x += "  <worldbody>\n";
  if (scene.ground) {
    // Ground contacts are the explicit pairs below, so the plane takes part in no other.
    x += "    <geom name=\"ground\" type=\"plane\" size=\"0 0 1\" pos=\"" +
         vec(scene.groundNormal * scene.groundHeight) + "\" zaxis=\"" + vec(scene.groundNormal) +
         "\" contype=\"0\" conaffinity=\"0\"/>\n";
  }
  BodyWriter bodies(scene, forest, x);
  for (const int root : forest.roots) bodies.write(root, 0);
  x += "  </worldbody>\n";

  double solidFriction = -1.0;
  bool frictionsDiffer = false;
  for (const Body& b : scene.bodies) {
    if (!b.solid()) continue;
    if (solidFriction >= 0.0 && solidFriction != b.friction) frictionsDiffer = true;
    solidFriction = b.friction;
  }
  if (frictionsDiffer)
    model.notes.push_back(
        "bodies of different friction meet with the larger coefficient (MuJoCo's rule), not the geometric "
        "mean");
  writeContacts(scene, x);
  writeTendons(scene, x);

  x += "  <equality>\n";
  bool apart = false;
  for (std::size_t k = 0; k < scene.pins.size(); ++k) {
    if (forest.pinInTree[k]) continue;
    // The connect's anchor is in body1's frame; MuJoCo finds body2's point from the pose the
    // model is written in, so a pin whose points start apart would be held apart.
    const Pin& p = scene.pins[k];
    if (glm::length(p.worldB - p.worldA) > 1e-9) apart = true;
    x += "    <connect body1=\"" + name('b', static_cast<std::size_t>(p.a)) + "\" body2=\"" +
         name('b', static_cast<std::size_t>(p.b)) + "\" anchor=\"" + vec(p.localA) + "\"/>\n";
    model.equalityRows += 3;
  }
  for (std::size_t k = 0; k < scene.distances.size(); ++k) {
    const Distance& d = scene.distances[k];
    if (!d.rigid()) continue;
    // With one tendon the equality holds its length at the reference (its length as written)
    // plus polycoef[0].
    const double offset = d.min - glm::length(d.worldB - d.worldA);
    x += "    <tendon tendon1=\"" + name('t', k) + "\" polycoef=\"" + num(offset) + " 0 0 0 0\"/>\n";
  }
  x += "  </equality>\n</mujoco>\n";
  if (apart) model.notes.push_back("pins whose points start apart held at their distance");
  if (scene.restitution > 0.0) model.notes.push_back("restitution not expressed");
  model.xml = std::move(x);
  return model;
}

}  // namespace lab::peers::mjcf
