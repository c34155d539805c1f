#pragma once
// Compares a scene as it was saved (scenes::writeSceneXml's input) with the scene its text
// reloads as, within tolerances that follow from what a round trip through a file can keep.
// Shared by the fuzzer (tests/fuzz/) and the round-trip property tests, so both hold the writer
// and the loader to the same contract (docs/scene-format.md, "Files the sandbox saves").
#include <string>

#include "scenes/scene.h"

namespace testsupport {

/// What a round trip may change, and why. Exact where the file holds the very double:
/// settings, counts, names, loose particles' positions, loose sticks and ranges, materials,
/// sizes, collision filters. Within a tolerance where the reloaded number is recomputed:
struct Tolerance {
  /// Relative to the size of the coordinates involved (|centre| + |half extents|, and the
  /// speed of a box's particles for its velocity): a box is saved as its fitted pose and
  /// rebuilt from it, through Euler angles, a quaternion, a polar decomposition and
  /// barycentric weights, each good to a few ulps (2.2e-16 each). 1e-12 leaves a margin of over
  /// a thousand ulps, and is still far below what a real fault makes: a lost deformation is
  /// about 1e-3 m, and a point out by a millimetre at a million metres is 1e-9 of it.
  double relative = 1e-12;
  /// An orientation (rad) is fitted from particles one box size apart, so it is known to the
  /// position's round-off over the box's middle half extent (the smaller extents cannot
  /// resolve a turn about the long axis; that term is added); this is the floor under it, the
  /// polar decomposition's own stopping point (it stops once an iteration changes less than
  /// 1e-14).
  double angle = 1e-12;
  /// Verlet keeps velocity as (x - x*) / h, so a velocity is only known to ulp(|x|) / h: a
  /// body at 1e6 m stepped at h = 1e-9 s cannot tell velocities 0.2 m/s apart. The velocity
  /// tolerance adds velocityUlps ulps of the position over h to the relative part.
  double velocityUlps = 64.0;
};

/// Empty when `reloaded` is `saved` as writeSceneXml wrote it, within `tolerance`; otherwise
/// the first difference found, naming the body or setting, both values and the tolerance.
/// Boxes are compared as rigid bodies (World::bodyPose, the rigid velocity and spin fitted to
/// their particles, mass), since a saved box loses the deformation its particles had; frozen
/// boxes as saved at rest with 1 kg; loose particles one by one; links by the world positions
/// of their two points; characters by their clips, clocks, strengths as last set and reaction
/// settings. The reloaded world's clock, drag, freezes and <expect> elements are not compared, nor
/// a character's reaction under way or a fade: a file does not hold them.
std::string compareScenes(const scenes::Scene& saved, const scenes::Scene& reloaded,
                          const Tolerance& tolerance = {});

}  // namespace testsupport
