#pragma once
// Measuring a run against a scene's pass criteria (stability_criteria.h): our world step by
// step, or a peer engine's run from the body poses it recorded (peer.h). A peer has no
// particles, sticks or contact report of ours, so its figures come from its poses, measured by
// one geometry code for every engine (peers/pose_measures.h).
#include <string>
#include <vector>

#include "physics/world.h"
#include "scenes/scene.h"
#include "stability_criteria.h"

namespace lab::stability {

/// One criterion in one run.
struct Verdict {
  bool judged = true;  ///< false: a peer's positions cannot answer it (`why` says why)
  std::string why;     ///< when not judged: "needs orientation", ...
  double value = 0.0;  ///< the figure measured, in the criterion's unit
  double ratio = 0.0;  ///< errorRatio(): <= 1 passes; infinity when the run blew up
  bool passed = false;
};

/// Counts a box's flips (Metric::Flips) from its orientations: the turns over of its middle
/// axis (that of its middle side, and of its middle moment of inertia) relative to where it
/// pointed at the window's start. Ours and the peers' are counted by this one code.
class FlipCounter {
 public:
  /// The box's middle axis in its own frame, from its half extents.
  static phys::Vec3 middleAxis(const phys::Vec3& halfExtents);
  /// The window's first sample: the middle axis, in the world, at its start.
  void start(const phys::Vec3& axis);
  /// Every later sample; counts a flip when the axis has swung more than 60 degrees past the
  /// plane across its last side.
  void sample(const phys::Vec3& axis);
  double flips() const { return flips_; }

 private:
  phys::Vec3 axisAtStart_{0.0};
  int sign_ = 1;  // which way the middle axis points now
  double flips_ = 0.0;
};

/// Follows our world through a run: observe() after loading (step 0) and after every step.
class WorldJudge {
 public:
  WorldJudge(const std::vector<Criterion>& criteria, const phys::World& world);

  /// Takes the state after `step` World::step() calls into every criterion whose window holds it.
  void observe(const phys::World& world, int step);
  /// The verdicts; `blewUp` (the guard froze something) fails every criterion with infinity.
  std::vector<Verdict> verdicts(bool blewUp) const;

 private:
  struct State {
    double value = 0.0;
    std::vector<phys::Vec3> reference;  // drift: the bodies at the window's start
    FlipCounter flips;
  };
  phys::Vec3 position(const phys::World& world, std::size_t body) const;
  void sampleDrift(const Criterion& c, State& s, const phys::World& world, int step) const;
  void sampleFlips(const Criterion& c, State& s, const phys::World& world, int step) const;

  const std::vector<Criterion>& criteria_;
  std::vector<phys::ParticleId> loose_;  // bodies.h's, so a criterion reads only its own bodies
  std::vector<State> states_;
};

/// A peer's run judged: `positions[k]` and `orientations[k]` are its bodies' poses (bodies.h
/// order) after step k + 1, for every step of the run; `scene` is the scene as loaded (step 0,
/// the sticks' lengths, and the peers' description of it). Drift, stays-behind, speed (of the
/// bodies' centres), stick-error (of sticks between loose particles: a peer's rigid bodies have
/// no error of their own), penetration and joint-gap (peers/pose_measures.h) and flips (the
/// FlipCounter on its orientations) are judged. With no orientations (empty), those needing
/// them are not judged and say why.
std::vector<Verdict> judgePeer(const std::vector<Criterion>& criteria, const scenes::Scene& scene, double dt,
                               const std::vector<std::vector<phys::Vec3>>& positions,
                               const std::vector<std::vector<phys::Quat>>& orientations);

}  // namespace lab::stability
