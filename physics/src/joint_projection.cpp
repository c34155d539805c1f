// The rigid joints' pins closed by a direct solve of each tree (physics/joint_projection.h).
//
// One Newton step solves, for the bodies' pose changes d (a translation and a small turn each) and
// the joints' multipliers l, the saddle-point system [M J^T; J 0] [d; l] = [0; -C]: the change of
// least kinetic metric d^T M d whose linearised constraints J d close the errors C (a pin's gap, a
// hinge's axes out of line). Its graph (bodies and
// joints as nodes, each joint joined to its two bodies) is a forest wherever the joints are, so
// eliminating the nodes children first fills nothing in, and the solve costs a few 3x3 products a
// joint (Baraff 1996, "Linear-time dynamics using Lagrange multipliers"). Blocks are at most 6x6:
// a body's (translation, turn), a joint's 3 rows (a cone's pin) or 5 (a hinge's pin and axes).
#include "physics/joint_projection.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "rigid_motion.h"
#include "union_find.h"

namespace phys {
namespace {

constexpr std::int32_t kNone = -1;

std::uint8_t rowsOf(const RigidJoint& j) {
  return j.kind == JointKind::Hinge ? 5 : 3;
}

bool movable(const RigidBodies& r, RigidId i) {
  const Vec3& d = r.inverseInertia[i];
  return r.inverseMass[i] > 0.0 && d.x > 0.0 && d.y > 0.0 && d.z > 0.0;
}

Vec3 pinGap(const RigidBodies& r, const RigidJoint& j) {
  return (r.position[j.b] + r.orientation[j.b] * j.pivotB) -
         (r.position[j.a] + r.orientation[j.a] * j.pivotA);
}

// A hinge's two axes, each in world axes.
void hingeAxes(const RigidBodies& r, const RigidJoint& j, Vec3& axisA, Vec3& axisB) {
  axisA = r.orientation[j.a] * j.axisA;
  axisB = r.orientation[j.b] * j.axisB;
}

// The joint's largest error: its pin's gap (m), and for a hinge the sine of its axes' angle.
Real jointError(const RigidBodies& r, const RigidJoint& j) {
  Real error = glm::length(pinGap(r, j));
  if (j.kind == JointKind::Hinge) {
    Vec3 axisA, axisB;
    hingeAxes(r, j, axisA, axisB);
    error = std::max(error, glm::length(glm::cross(axisA, axisB)));
  }
  return error;
}

// In place, the inverse of the N x N leading block of a row-major 6x6 matrix by Gauss-Jordan
// without pivoting, which a definite matrix (a body's, positive; a joint's, negative) never needs.
// False when a pivot is not a finite non-zero number. N is fixed so that the loops unroll.
template <int N>
bool invertBlock(std::array<Real, 36>& m) {
  for (int k = 0; k < N; ++k) {
    const Real pivot = m[k * 6 + k];
    if (!(std::abs(pivot) > 0.0) || !std::isfinite(pivot)) return false;
    const Real inverse = 1.0 / pivot;
    m[k * 6 + k] = 1.0;
    for (int c = 0; c < N; ++c) m[k * 6 + c] *= inverse;
    for (int i = 0; i < N; ++i) {
      if (i == k) continue;
      const Real f = m[i * 6 + k];
      m[i * 6 + k] = 0.0;
      for (int c = 0; c < N; ++c) m[i * 6 + c] -= f * m[k * 6 + c];
    }
  }
  return true;
}

bool invert(std::array<Real, 36>& m, int n) {
  return n == 5 ? invertBlock<5>(m) : invertBlock<3>(m);
}

// out = the N x N leading block of m times v's first N entries.
template <int N>
void multiplyBlock(const std::array<Real, 36>& m, const std::array<Real, 6>& v, std::array<Real, 6>& out) {
  for (int a = 0; a < N; ++a) {
    Real sum = 0.0;
    for (int k = 0; k < N; ++k) sum += m[a * 6 + k] * v[k];
    out[a] = sum;
  }
}

void multiply(const std::array<Real, 36>& m, int n, const std::array<Real, 6>& v, std::array<Real, 6>& out) {
  if (n == 5)
    multiplyBlock<5>(m, v, out);
  else
    multiplyBlock<3>(m, v, out);
}

bool allFinite(const std::array<Real, 6>& v) {
  return std::all_of(v.begin(), v.end(), [](Real x) { return std::isfinite(x); });
}

}  // namespace

// Joints are taken into the forest one by one in the world's order: one that would close a loop is
// left out, and so is one that would tie a tree to a second body that cannot move (a frozen or
// sleeping body is no node: a joint to it is the root of its tree, and a second such joint would
// ask two immovable points of one tree).
void JointProjection::buildTrees(const RigidBodies& r, std::span<const RigidJoint> joints) {
  const std::size_t n = r.size();
  // Room for every body and joint at once, so that bodies waking or thawing later (more nodes)
  // never make a step allocate.
  const std::size_t most = n + joints.size();
  nodes_.reserve(most);
  treeJoints_.reserve(joints.size());
  adjacency_.reserve(2 * joints.size());
  body_.reserve(most);
  joint_.reserve(most);
  rhs_.reserve(most);
  root_.resize(n);
  std::iota(root_.begin(), root_.end(), 0u);
  anchored_.assign(n, 0);
  treeJoints_.clear();
  for (std::uint32_t k = 0; k < joints.size(); ++k) {
    const RigidJoint& j = joints[k];
    const bool ma = movable(r, j.a), mb = movable(r, j.b);
    if (!ma && !mb) continue;
    if (ma && mb) {
      const std::uint32_t ra = detail::findRoot(root_, j.a.index), rb = detail::findRoot(root_, j.b.index);
      if (ra == rb || (anchored_[ra] != 0 && anchored_[rb] != 0)) continue;
      const std::uint8_t anchored = anchored_[ra] | anchored_[rb];
      detail::unite(root_, ra, rb);
      anchored_[std::min(ra, rb)] = anchored;
    } else {
      const std::uint32_t rm = detail::findRoot(root_, ma ? j.a.index : j.b.index);
      if (anchored_[rm] != 0) continue;
      anchored_[rm] = 1;
    }
    treeJoints_.push_back(k);
  }

  // Each movable body's tree joints, in the world's order.
  adjacencyStart_.assign(n + 1, 0);
  for (const std::uint32_t k : treeJoints_) {
    const RigidJoint& j = joints[k];
    if (movable(r, j.a)) ++adjacencyStart_[j.a + 1];
    if (movable(r, j.b)) ++adjacencyStart_[j.b + 1];
  }
  std::partial_sum(adjacencyStart_.begin(), adjacencyStart_.end(), adjacencyStart_.begin());
  adjacency_.resize(adjacencyStart_[n]);
  root_.assign(adjacencyStart_.begin(), adjacencyStart_.end() - 1);  // reused as each body's fill
  for (const std::uint32_t k : treeJoints_) {
    const RigidJoint& j = joints[k];
    if (movable(r, j.a)) adjacency_[root_[j.a]++] = k;
    if (movable(r, j.b)) adjacency_[root_[j.b]++] = k;
  }

  // Breadth first from each root, so that parents come before children: trees tied to an immovable
  // body from that joint, the others from their first body.
  nodes_.clear();
  bodyNode_.assign(n, kNone);
  const auto grow = [&] {
    for (std::size_t head = nodes_.size() - 1; head < nodes_.size(); ++head) {
      const Node node = nodes_[head];
      const auto at = static_cast<std::int32_t>(head);
      if (node.rows == 6) {
        const std::int32_t parent = node.parent;
        for (std::uint32_t e = adjacencyStart_[node.index]; e < adjacencyStart_[node.index + 1]; ++e) {
          if (parent != kNone && nodes_[parent].index == adjacency_[e]) continue;
          nodes_.push_back({adjacency_[e], at, rowsOf(joints[adjacency_[e]])});
        }
      } else {
        for (const RigidId side : {joints[node.index].a, joints[node.index].b}) {
          if (!movable(r, side) || bodyNode_[side] != kNone) continue;
          bodyNode_[side] = static_cast<std::int32_t>(nodes_.size());
          nodes_.push_back({side.index, at, 6});
        }
      }
    }
  };
  for (const std::uint32_t k : treeJoints_) {
    if (movable(r, joints[k].a) && movable(r, joints[k].b)) continue;
    nodes_.push_back({k, kNone, rowsOf(joints[k])});
    grow();
  }
  for (std::uint32_t b = 0; b < n; ++b) {
    if (adjacencyStart_[b] == adjacencyStart_[b + 1] || bodyNode_[b] != kNone) continue;
    bodyNode_[b] = static_cast<std::int32_t>(nodes_.size());
    nodes_.push_back({b, kNone, 6});
    grow();
  }
  for (const Node& node : nodes_) {
    if (node.parent != kNone) nodes_[static_cast<std::size_t>(node.parent)].leaf = false;
  }
}

Real JointProjection::measure(const RigidBodies& r, std::span<const RigidJoint> joints) const {
  Real widest = 0.0;
  for (const std::uint32_t k : treeJoints_) widest = std::max(widest, jointError(r, joints[k]));
  return widest;
}

// One Newton step: the system at the poses as they are, eliminated children first and solved back
// parents first; then every body of the trees moved by its share. A joint's Jacobian for its body b
// is [[I, X], [0, W]], X = -[arm]x (the pivot moves by dx + dtheta x arm) and W's rows u^T and v^T
// (a hinge's axes' cross product, in the two directions u and v normal to A's axis, changes by the
// two bodies' relative turn in those directions); for a, the same negated. The products below are
// those of J D^-1 J^T and J^T D^-1 J written out in 3x3 blocks, the zeros of J left out.
bool JointProjection::solve(RigidBodies& r, std::span<const RigidJoint> joints) {
  const std::size_t count = nodes_.size();
  body_.resize(count);
  joint_.resize(count);
  rhs_.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const Node& node = nodes_[i];
    Vector6& rhs = rhs_[i];
    rhs.fill(0.0);
    if (node.rows == 6) {
      // A leaf's block is never added to, so it is set to its inverse at once.
      const RigidId b(node.index);
      const Vec3 inverse = r.inverseInertia[b];
      if (node.leaf) {
        body_[i] = {glm::dmat3(r.inverseMass[b]), glm::dmat3(0.0),
                    detail::worldInverseInertia(r.orientation[b], inverse)};
      } else {
        body_[i] = {glm::dmat3(1.0 / r.inverseMass[b]), glm::dmat3(0.0),
                    detail::worldInverseInertia(r.orientation[b],
                                                Vec3(1.0 / inverse.x, 1.0 / inverse.y, 1.0 / inverse.z))};
      }
      continue;
    }
    const RigidJoint& j = joints[node.index];
    JointRows& rows = joint_[i];
    const Vec3 armA = r.orientation[j.a] * j.pivotA, armB = r.orientation[j.b] * j.pivotB;
    const Vec3 gap = (r.position[j.b] + armB) - (r.position[j.a] + armA);
    rows.xa = -detail::crossMatrix(armA);
    rows.xb = -detail::crossMatrix(armB);
    rows.block.fill(0.0);
    rows.u = rows.v = Vec3(0.0);
    for (int k = 0; k < 3; ++k) rhs[k] = -gap[k];
    if (node.rows == 5) {
      Vec3 axisA, axisB;
      hingeAxes(r, j, axisA, axisB);
      const Vec3 other = std::abs(axisA.x) < 0.9 ? Vec3(1.0, 0.0, 0.0) : Vec3(0.0, 1.0, 0.0);
      rows.u = glm::normalize(glm::cross(axisA, other));
      rows.v = glm::cross(axisA, rows.u);
      const Vec3 apart = glm::cross(axisA, axisB);
      rhs[3] = -glm::dot(rows.u, apart);
      rhs[4] = -glm::dot(rows.v, apart);
    }
  }
  // Joint node k's side for the body `body`, one of its two: the sign of its Jacobian and its X.
  const auto side = [&](std::size_t k, std::uint32_t body, Real& sign) -> const glm::dmat3& {
    const bool isB = joints[nodes_[k].index].b.index == body;
    sign = isB ? 1.0 : -1.0;
    return isB ? joint_[k].xb : joint_[k].xa;
  };

  for (std::size_t i = count; i-- > 0;) {
    const Node& node = nodes_[i];
    if (node.rows == 6) {
      Block6& m = body_[i];
      if (!node.leaf) {  // D to D^-1 by its Schur complement
        const glm::dmat3 aInverse = glm::inverse(m.a);
        const glm::dmat3 aInverseB = aInverse * m.b;
        const glm::dmat3 sInverse = glm::inverse(m.c - glm::transpose(m.b) * aInverseB);
        const glm::dmat3 q = -aInverseB * sInverse;
        m = {aInverse - q * glm::transpose(aInverseB), q, sInverse};
      }
      if (node.parent == kNone) continue;
      // The parent joint's block less J D^-1 J^T, its right-hand side less J D^-1 rhs.
      const auto p = static_cast<std::size_t>(node.parent);
      Real s = 0.0;
      const glm::dmat3& x = side(p, node.index, s);
      JointRows& parent = joint_[p];
      const glm::dmat3 g = m.b + x * m.c;
      const glm::dmat3 pin = m.a + x * glm::transpose(m.b) + g * glm::transpose(x);
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) parent.block[a * 6 + c] -= pin[c][a];
      const Vec3 t(rhs_[i][0], rhs_[i][1], rhs_[i][2]), rr(rhs_[i][3], rhs_[i][4], rhs_[i][5]);
      const Vec3 y1 = m.a * t + m.b * rr, y2 = glm::transpose(m.b) * t + m.c * rr;
      const Vec3 pinRhs = s * (y1 + x * y2);
      for (int a = 0; a < 3; ++a) rhs_[p][a] -= pinRhs[a];
      if (nodes_[p].rows == 5) {
        const Vec3 gu = g * parent.u, gv = g * parent.v, cu = m.c * parent.u, cv = m.c * parent.v;
        for (int a = 0; a < 3; ++a) {
          parent.block[a * 6 + 3] -= gu[a];
          parent.block[3 * 6 + a] -= gu[a];
          parent.block[a * 6 + 4] -= gv[a];
          parent.block[4 * 6 + a] -= gv[a];
        }
        parent.block[3 * 6 + 3] -= glm::dot(parent.u, cu);
        parent.block[3 * 6 + 4] -= glm::dot(parent.u, cv);
        parent.block[4 * 6 + 3] -= glm::dot(parent.v, cu);
        parent.block[4 * 6 + 4] -= glm::dot(parent.v, cv);
        rhs_[p][3] -= s * glm::dot(parent.u, y2);
        rhs_[p][4] -= s * glm::dot(parent.v, y2);
      }
    } else {
      JointRows& rows = joint_[i];
      if (!invert(rows.block, node.rows)) return false;  // cannot happen for finite masses: move nothing
      if (node.parent == kNone) continue;
      // The parent body's block less J^T D^-1 J, its right-hand side less J^T D^-1 rhs.
      const auto p = static_cast<std::size_t>(node.parent);
      Real s = 0.0;
      const glm::dmat3& x = side(i, nodes_[p].index, s);
      const Matrix6& d = rows.block;
      glm::dmat3 pin;
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) pin[c][a] = d[a * 6 + c];
      const Vec3 q1(d[0 * 6 + 3], d[1 * 6 + 3], d[2 * 6 + 3]), q2(d[0 * 6 + 4], d[1 * 6 + 4], d[2 * 6 + 4]);
      const glm::dmat3 xt = glm::transpose(x);
      const glm::dmat3 h = pin * x + glm::outerProduct(q1, rows.u) + glm::outerProduct(q2, rows.v);
      const Vec3 k1 = xt * q1 + d[3 * 6 + 3] * rows.u + d[3 * 6 + 4] * rows.v;
      const Vec3 k2 = xt * q2 + d[4 * 6 + 3] * rows.u + d[4 * 6 + 4] * rows.v;
      Block6& parent = body_[p];
      parent.a -= pin;
      parent.b -= h;
      parent.c -= xt * h + glm::outerProduct(rows.u, k1) + glm::outerProduct(rows.v, k2);
      Vector6 z{};
      multiply(d, node.rows, rhs_[i], z);
      const Vec3 zp(z[0], z[1], z[2]);
      const Vec3 turn = xt * zp + z[3] * rows.u + z[4] * rows.v;
      for (int a = 0; a < 3; ++a) {
        rhs_[p][a] -= s * zp[a];
        rhs_[p][3 + a] -= s * turn[a];
      }
    }
  }

  for (std::size_t i = 0; i < count; ++i) {
    const Node& node = nodes_[i];
    Vector6& solution = rhs_[i];
    if (node.rows == 6) {
      Vec3 t(solution[0], solution[1], solution[2]), rr(solution[3], solution[4], solution[5]);
      if (node.parent != kNone) {  // less J^T l of the parent joint
        const auto p = static_cast<std::size_t>(node.parent);
        Real s = 0.0;
        const glm::dmat3& x = side(p, node.index, s);
        const Vector6& l = rhs_[p];
        const Vec3 lp(l[0], l[1], l[2]);
        t -= s * lp;
        rr -= s * (glm::transpose(x) * lp + l[3] * joint_[p].u + l[4] * joint_[p].v);
      }
      const Block6& m = body_[i];
      const Vec3 dx = m.a * t + m.b * rr, turn = glm::transpose(m.b) * t + m.c * rr;
      solution = {dx.x, dx.y, dx.z, turn.x, turn.y, turn.z};
      continue;
    }
    Vector6 t = solution;
    if (node.parent != kNone) {  // less J d of the parent body
      const auto p = static_cast<std::size_t>(node.parent);
      Real s = 0.0;
      const glm::dmat3& x = side(i, nodes_[p].index, s);
      const Vector6& d = rhs_[p];
      const Vec3 dx(d[0], d[1], d[2]), turn(d[3], d[4], d[5]);
      const Vec3 pin = s * (dx + x * turn);
      for (int a = 0; a < 3; ++a) t[a] -= pin[a];
      t[3] -= s * glm::dot(joint_[i].u, turn);
      t[4] -= s * glm::dot(joint_[i].v, turn);
    }
    multiply(joint_[i].block, node.rows, t, solution);
  }

  for (std::size_t i = 0; i < count; ++i) {
    if (nodes_[i].rows == 6 && !allFinite(rhs_[i])) return false;
  }
  for (std::size_t i = 0; i < count; ++i) {
    if (nodes_[i].rows != 6) continue;
    const RigidId b(nodes_[i].index);
    const Vector6& x = rhs_[i];
    r.position[b] += Vec3(x[0], x[1], x[2]);
    r.orientation[b] = detail::turned(r.orientation[b], Vec3(x[3], x[4], x[5]));
  }
  return true;
}

JointProjectionReport JointProjection::project(RigidBodies& r, std::span<const RigidJoint> joints,
                                               const JointProjectionSettings& settings) {
  JointProjectionReport report;
  if (joints.empty()) return report;
  buildTrees(r, joints);
  if (treeJoints_.empty()) return report;
  report.errorBefore = report.errorAfter = measure(r, joints);
  while (report.errorAfter > settings.tolerance && report.iterations < settings.iterations) {
    if (!solve(r, joints)) break;
    ++report.iterations;
    report.errorAfter = measure(r, joints);
  }
  return report;
}

}  // namespace phys
