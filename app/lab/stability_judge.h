#pragma once
// Measuring a run against a scene's pass criteria (stability_criteria.h): our world step by
// step, or a peer engine's run from the body poses it recorded (peer.h). A peer has no
// particles, sticks or contact report of ours, so its figures come from its poses, measured by
// one geometry code for every engine (peers/pose_measures.h).
#include <cstddef>
#include <functional>
#include <optional>
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
  double ratio = 0.0;  ///< errorRatio(): <= 1 passes; infinity when the run blew up or never flipped
  bool passed = false;
};

/// One criterion's figure over its window, step by step: the one code for our world and a
/// peer's poses. Drift, stays-behind and flips read the poses of the criterion's own bodies; the
/// other metrics take a figure of the whole step (World::metrics(), or a peer's from its poses).
class Tally {
 public:
  /// `loaded`: the scene's world, whose box gives flips its middle axis.
  Tally(const Criterion& criterion, const phys::World& loaded);

  /// The poses after `step`, a step of the window: body b's (bodies.h order) centre and turn.
  void samplePoses(int step, const std::function<phys::Vec3(std::size_t)>& position,
                   const std::function<phys::Quat(std::size_t)>& orientation);
  /// A figure of the step: the largest counts, and infinity once one is not finite.
  void sampleFigure(double figure);
  double value() const { return value_; }
  /// Whether the criterion has failed in a way no later sample can undo: every figure only moves
  /// toward failing (the largest sample, the extreme toward the plane, a count of flips), but for
  /// a count of flips under its min, which may yet reach it.
  bool failedForGood() const;

 private:
  const Criterion* criterion_;
  double value_;
  std::vector<phys::Vec3> reference_;  // drift: the bodies at the window's start
  // Flips: the box's middle axis (that of its middle side, and of its middle moment of inertia)
  // in its own frame; in the world at the window's start; and which way it points now.
  phys::Vec3 middleAxis_{0.0}, axisAtStart_{0.0};
  int sign_ = 1;
};

/// Follows our world through a run: observe() after loading (step 0) and after every step.
class WorldJudge {
 public:
  WorldJudge(const std::vector<Criterion>& criteria, const phys::World& world);

  /// Takes the state after `step` World::step() calls into every criterion whose window holds it.
  void observe(const phys::World& world, int step);
  /// The verdicts; `blewUp` (the guard froze something) fails every criterion with infinity.
  std::vector<Verdict> verdicts(bool blewUp) const;
  /// The first criterion (its index) that has failed for good (Tally::failedForGood), if any: from
  /// then on the run fails whatever its later steps do.
  std::optional<std::size_t> failedForGood() const;

 private:
  const std::vector<Criterion>& criteria_;
  std::vector<phys::ParticleId> loose_;  // bodies.h's, so a criterion reads only its own bodies
  std::vector<Tally> tallies_;
};

/// A peer's run judged: `positions[k]` and `orientations[k]` are its bodies' poses (bodies.h
/// order) after step k + 1, for every step of the run; `scene` is the scene as loaded (step 0,
/// the sticks' lengths, and the peers' description of it). Drift, stays-behind, speed (of the
/// bodies' centres), stick-error (of sticks between loose particles: a peer's rigid bodies have
/// no error of their own), penetration and joint-gap (peers/pose_measures.h) and flips (its
/// orientations, counted by our Tally) are judged. With no orientations (empty), those needing
/// them are not judged and say why.
std::vector<Verdict> judgePeer(const std::vector<Criterion>& criteria, const scenes::Scene& scene, double dt,
                               const std::vector<std::vector<phys::Vec3>>& positions,
                               const std::vector<std::vector<phys::Quat>>& orientations);

}  // namespace lab::stability
