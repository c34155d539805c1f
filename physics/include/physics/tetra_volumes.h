#pragma once
// The tetra model's volume constraint, for its flat bodies (docs/physics.md, "Boxes", its paragraph
// "Flat tetra bodies"): the tetrahedral volume constraint of Bender, Müller and Macklin
// ("Position-Based Simulation Methods in Computer Graphics", Eurographics 2015 tutorial). A tetra
// body's 6 sticks resist a change of its tetrahedron's thickness t across a width w only as
// (t / w)^2 per pass, so a slab lying on the ground let its top particles sink through its bottom
// ones and turned inside out. The volume's gradient at each particle is its opposite face's normal,
// which resists that squarely, and its sign keeps the tetrahedron from turning inside out.
#include <vector>

#include "physics/body.h"
#include "physics/particles.h"
#include "physics/types.h"
#include "physics/workers.h"

namespace phys {

class TetraVolumes {
 public:
  /// Keeps the volume of a tetra box whose thinnest side is under half its middle one, and gives any
  /// other tetra body its volume back once under kVolumeFloor of it, with its sign; a body of another
  /// model adds nothing. Called once for each body as it is added, its particles already added.
  void addBody(const Body& body);
  /// Share of its rest volume, signed, below which a tetra body that is not flat (inside out, or
  /// crushed to under half) is projected back to its whole volume; above it nothing moves. Back to
  /// the floor only, a body past flat stayed there, the sticks pulling it on to its mirror image
  /// and the floor pulling it back (a capsule landing at dt 1/20 s rested at 53% of its volume).
  static constexpr Real kVolumeFloor = 0.5;

  /// One Gauss-Seidel projection of each kept body's volume, and of each other tetra body's under
  /// its floor (back to its whole volume), before each pass over the sticks.
  /// `alongStart`: along the gradient at x* (SHAKE's way, as it moves each stick along its direction
  /// at the substep's start) rather than at x.
  /// The floors are looked at in ranges of bodies on the step's threads (each body's particles are
  /// its own), so that two threads do not wait on one reading what the other just moved.
  /// `keepSpin` (SolverSettings::keepSpin) keeps each projected body's moment through its projection
  /// as the passes keep it through its sticks: the volume's gradient at the moving tetrahedron takes
  /// angular momentum as a stick's direction does.
  void keep(Particles& p, bool alongStart, const Workers* workers = nullptr, bool keepSpin = false) const;

 private:
  struct Kept {
    ParticleId first;    // the first of its four particles
    Real restSixVolume;  // six times the rest tetrahedron's signed volume
  };
  static void project(Particles& p, const Kept& k, Real targetSixVolume, bool alongStart, bool keepSpin);

  std::vector<Kept> kept_;     // flat boxes: their rest volume
  std::vector<Kept> floored_;  // every other tetra body: its volume back once under kVolumeFloor of it
};

}  // namespace phys
