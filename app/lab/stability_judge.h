#pragma once
// Measuring a run against a scene's pass criteria (stability_criteria.h): our world step by
// step, or a peer engine's run from the body positions it recorded (peer.h), which is all a
// peer gives, so a peer is judged only on the criteria positions can answer.
#include <string>
#include <vector>

#include "physics/world.h"
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

/// Follows our world through a run: observe() after loading (step 0) and after every step.
class WorldJudge {
 public:
  WorldJudge(const std::vector<Criterion>& criteria, const phys::World& world);

  /// Takes the state after `step` World::step() calls into every criterion whose window holds it.
  void observe(const phys::World& world, int step);
  /// The verdicts; `blewUp` (the guard froze something) fails every criterion with infinity.
  std::vector<Verdict> verdicts(bool blewUp) const;

 private:
  struct BodyRef {  // a body of bodies.h order: a box, or a loose particle
    bool box = true;
    std::uint32_t id = 0;
  };
  struct State {
    double value = 0.0;
    std::vector<phys::Vec3> reference;  // drift: the bodies at the window's start
    phys::Vec3 axisAtStart{0.0};        // flips: the middle axis at the window's start
    int sign = 1;                       // flips: which way the middle axis points now
  };
  phys::Vec3 position(const phys::World& world, std::size_t body) const;
  void sampleDrift(const Criterion& c, State& s, const phys::World& world, int step) const;
  void sampleFlips(const Criterion& c, State& s, const phys::World& world, int step) const;

  const std::vector<Criterion>& criteria_;
  std::vector<BodyRef> bodies_;
  std::vector<State> states_;
};

/// A peer's run judged: `positions[k]` are the bodies (bodies.h order) after step k + 1, for
/// every step of the run; `world` is the scene as loaded (step 0, and the sticks' lengths).
/// Drift, stays-behind, speed (of the bodies' centres) and stick-error (of sticks between loose
/// particles, when the scene has any: a peer's rigid bodies have no error of their own) are
/// judged; the rest are not, and say why.
std::vector<Verdict> judgePositions(const std::vector<Criterion>& criteria, const phys::World& world, double dt,
                                    const std::vector<std::vector<phys::Vec3>>& positions);

}  // namespace lab::stability
