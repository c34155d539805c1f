#pragma once
// Pushes: a force held on a body for a while (World::push), what the sandbox's push and a scene's
// timed shove apply. It acts with gravity, before the passes, as the mouse spring does, so a 200 N
// push for 0.2 s gives any body the impulse 40 N s, whatever the substeps.
#include "physics/types.h"

namespace phys {

/// A force on a body at a point of it, for a time.
struct Push {
  BodyId body{};
  Vec3 local{0.0};     ///< unit: m; where it acts, from the body's centre in the body's frame
  Vec3 force{0.0};     ///< unit: N; in the world
  Real remaining = 0;  ///< unit: s; how much longer it acts
};

}  // namespace phys
