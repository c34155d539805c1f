#pragma once
// What a step will cost, estimated from the world's size and settings before it is taken, so
// the soak test can keep every command short without timing anything (a sequence that depended
// on timing could not be replayed from its seed).
//
// The unit is a "visit": one particle, stick or link relaxed once (a contact point counts 3:
// its projection and its friction). One step of a world visits each of them iterations x
// substeps times; each pass also costs about 30 visits of its own and each substep 50 (timers
// and bookkeeping, which make 1000 x 1000 substeps and iterations of an empty world 0.4 s), and
// each substep fits every box's frame (about 20) and tests every broad-phase pair (about 70;
// the pairs are counted as the broad phase will count them, see estimatedPairs). Measured over
// the project's scenes at 1 to 64 substeps and iterations (release build, a 2-core machine
// shared with two compilers), a visit costs 3 to 35 ns, mostly 5 to 25.
#include "session.h"

namespace soak {

/// One step may cost up to this, 0.25 to 1.2 s: 1000 iterations x 1000 substeps fit in an empty
/// (cleared) world and on the one-particle and two-particle scenes (the orbits, the pendulums),
/// which is where the extremes get stepped as they are.
inline constexpr double kMaxVisitsPerStep = 5e7;
/// A step command takes as many steps as fit in this, and at least one. 0.05 to 0.25 s.
inline constexpr double kMaxVisitsPerCommand = 1e7;

/// Box pairs the broad phase of the next step will find, estimated as it finds them.
double estimatedPairs(const phys::World& world);

/// Visits of the next World::step of `world`, under its own settings.
double stepVisits(const phys::World& world);

/// Visits of `steps` calls of Session::step: run 0 takes each of them, and every other run of
/// the method overlay as many of its own as it needs to reach run 0's time (at most 1000 per
/// call, as Session::step allows).
double sessionVisits(const sandbox::Session& session, int steps);

}  // namespace soak
