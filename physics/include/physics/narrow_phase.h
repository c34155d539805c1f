#pragma once
// The narrow phase (Stage::NarrowPhase): turns the broad phase's pairs into manifolds, each a
// pair's contact points embedded in its two bodies' particles, once per step with a speculative
// margin, and measures them again from those points in every substep (docs/physics.md, "Contacts
// once per step"). It owns the points, the manifolds and the per-point state the passes keep.
#include <cstdint>
#include <span>
#include <vector>

#include "physics/body.h"
#include "physics/broad_phase.h"
#include "physics/collision.h"
#include "physics/constraints.h"
#include "physics/particles.h"
#include "physics/rigid_contacts.h"
#include "physics/workers.h"

namespace phys {

/// The contact of one pair of bodies: its points are contacts() [firstContact, firstContact +
/// contactCount), or rigidContacts() when either body is rigid, all with the pair's normal.
struct Manifold {
  BodyId a{}, b{};
  bool rigid = false;  ///< either body is rigid: its points are in rigidContacts()
  std::uint32_t firstContact = 0, contactCount = 0;
  Vec3 normal{0.0};    ///< from a towards b
  Real overlap = 0.0;  ///< unit: m; the deepest point's overlap beyond the slop at x*; < 0 when apart
  /// Its points hold for the whole step (face on face); every other manifold is collided again in
  /// every substep.
  bool kept = false;
  /// The axis of the separating-axis test that made it (SatResult::axis; a capsule's: -1), which
  /// the pair's next test is given (satTest's previousAxis).
  int axis = -1;
  BodyId reference{};     ///< kept: the body whose face the normal is
  Vec3 localNormal{0.0};  ///< kept: the normal in that body's frame
  /// kept: where b was in a's frame when the manifold was made (its centre, unit m, and its axes),
  /// against which NarrowPhase::build decides whether to carry it into the next step.
  Obb madeAt;
  /// kept: the clipping dropped no point, so every corner of the faces' overlap is here; only
  /// such a manifold is carried into the next step.
  bool whole = false;
  /// kept: the reference body's axes when the normal and the points' friction anchors were last
  /// turned with it.
  glm::dmat3 turnedAxes{1.0};
};

/// What the passes keep per contact point, index for index with NarrowPhase::contacts().
struct BodyContactState {
  std::vector<Real> push;             ///< unit: m; the push of the last pass
  std::vector<std::uint8_t> touched;  ///< pushed in this substep
  std::vector<Real> approach;         ///< unit: m/s; approach speed at the substep's start
  std::vector<Real> allowance;        ///< unit: m; overlap at x*, then what the point may keep
};

/// What the narrow phase reads of the world in a substep.
struct NarrowPhaseInput {
  const Particles& particles;
  const RigidBodies& rigid;
  std::span<const Body> bodies;
  std::span<const Obb> frames;  ///< each body's frame in this substep
  const BroadPhase& broadPhase;
  Real featureEpsilon = 0.0;  ///< unit: m (SolverSettings::featureEpsilon)
  Real contactSlop = 0.0;     ///< unit: m (SolverSettings::contactSlop)
  Real dt = 0.0;              ///< unit: s; the step
  Real gravity = 0.0;         ///< unit: m/s^2; |g|
  ManifoldReuseSettings reuse;
  std::span<const std::uint8_t> asleep;  ///< per body, 1 when asleep (Islands); empty when none is
  const Workers* workers = nullptr;      ///< the step's threads; null on one
};

class NarrowPhase {
 public:
  /// Makes room for the manifolds and points of `pairs` pairs among `bodies` bodies (room.h), from
  /// the last substep's count, before any is made, so that the step does not allocate; and the
  /// same room in each of the pieces that `threads` threads would collide at once.
  void reserve(std::size_t pairs, std::size_t bodies, int threads);
  /// After the broad phase found its pairs: every pair's manifold, its points kept when they are
  /// nearer than the pair can close in the step (speculativeMargin). A face-on-face manifold of
  /// the last step whose bodies have stayed within ManifoldReuseSettings of where they were to each
  /// other when it was made is carried over, points, reference face and all.
  void build(const NarrowPhaseInput& in);
  /// build() again, right after it, from the same manifolds it carried from (those of the last
  /// substep, not its own): for pairs it skipped, two sleeping bodies of which an island woke since
  /// (World::wakeTouched). The pairs it found before are found again from the bounds the broad
  /// phase measured again: a body that World::stopFastBodies moved has a shorter travel there, so
  /// its pairs' speculative margins may be narrower than in the first build.
  void rebuild(const NarrowPhaseInput& in);
  /// In the step's other substeps: kept manifolds follow their reference face; the others are
  /// collided again.
  void refresh(const NarrowPhaseInput& in);
  /// Each point's overlap at x*, where the substep starts (a particle pair's beyond the slop; a
  /// rigid pair's at the bodies' previous poses), each manifold's deepest, and no point touched yet. An
  /// overlap deeper than the feature epsilon of a pair that moved past each other's half thickness is checked
  /// against the two bodies' frames at x*: if those were apart, it was no overlap (see the .cpp).
  void measureStarts(const NarrowPhaseInput& in);

  /// How far apart two bodies' points can be and still close within the step. unit: m
  static Real speculativeMargin(const NarrowPhaseInput& in, BodyId a, BodyId b);

  /// Points of pairs of particle bodies.
  std::span<const BodyContact> contacts() const { return contacts_; }
  /// The same, for the stages that move the kept points' friction anchors: friction as they slip,
  /// the parting as it moves bodies.
  std::span<BodyContact> movableContacts() { return contacts_; }
  /// What each point of contacts() carries that the passes seldom read, at the same index.
  std::span<const BodyContactExtra> contactExtras() const { return extras_; }
  /// Points of pairs with a rigid body.
  std::span<const RigidContact> rigidContacts() const { return rigidContacts_; }
  std::span<RigidContact> rigidContacts() { return rigidContacts_; }
  RigidContactState& rigidState() { return rigidState_; }
  const RigidContactState& rigidState() const { return rigidState_; }
  std::span<const Manifold> manifolds() const { return manifolds_; }
  BodyContactState& state() { return state_; }
  const BodyContactState& state() const { return state_; }

 private:
  /// Where a run of pairs puts its manifolds and points: the narrow phase's own arrays, or a
  /// piece's, whose firstContact count from the piece's first point.
  struct Sink {
    std::vector<Manifold>& manifolds;
    std::vector<BodyContact>& contacts;
    std::vector<BodyContactExtra>& extras;  ///< one a contact
    std::vector<RigidContact>& rigidContacts;
  };
  struct Piece {
    std::vector<Manifold> manifolds;
    std::vector<BodyContact> contacts;
    std::vector<BodyContactExtra> extras;
    std::vector<RigidContact> rigidContacts;
  };
  /// work(sink, begin, end) over [0, count): at once in contiguous pieces of at least perPiece on
  /// the step's threads, each into its own sink, then the pieces appended in order, so the arrays
  /// are what one run over all of it makes.
  template <class Work>
  void inPieces(const NarrowPhaseInput& in, std::size_t count, std::size_t perPiece, Work&& work);
  void append(Piece& piece);
  void buildRange(const NarrowPhaseInput& in, std::size_t begin, std::size_t end, Sink& out) const;
  void refreshRange(const NarrowPhaseInput& in, std::size_t begin, std::size_t end, Sink& out) const;
  void swapToSpare();
  template <class Passed>
  void measureStart(const NarrowPhaseInput& in, Manifold& m, const Passed& passed);

  bool collidePair(const NarrowPhaseInput& in, BodyId a, BodyId b, int previousAxis,
                   BoxContact& contact) const;
  static void addManifold(const NarrowPhaseInput& in, BodyId a, BodyId b, const BoxContact& contact,
                          Sink& out);
  static void turnNormal(const NarrowPhaseInput& in, Manifold& manifold, BodyContact* contacts);
  static void anchor(BodyContact& c, const BodyContactExtra& extra, const Vec3& startApart);
  void carrySlide(const NarrowPhaseInput& in, const Manifold& old, std::span<const BodyContact> made,
                  std::span<BodyContactExtra> madeExtras) const;
  bool canCarry(const NarrowPhaseInput& in, const Manifold& m) const;
  void carry(const NarrowPhaseInput& in, const Manifold& m, Sink& out) const;
  void sizeState();

  static void pushManifold(const NarrowPhaseInput& in, BodyId a, BodyId b, const BoxContact& contact,
                           bool rigid, std::size_t first, Sink& out);
  static void addRigidManifold(const NarrowPhaseInput& in, BodyId a, BodyId b, const BoxContact& contact,
                               Sink& out);
  static void turnRigidNormal(const NarrowPhaseInput& in, Manifold& m, RigidContact* contacts);

  std::vector<BodyContact> contacts_;
  std::vector<BodyContactExtra> extras_;  // contacts_'s, at the same index
  std::vector<RigidContact> rigidContacts_;
  std::vector<RigidContact> spareRigidContacts_;
  RigidContactState rigidState_;
  std::vector<Manifold> manifolds_;
  BodyContactState state_;
  std::vector<Manifold> spareManifolds_;       // manifolds_'s room for refresh
  std::vector<BodyContact> spareContacts_;     // contacts_'s room for refresh
  std::vector<BodyContactExtra> spareExtras_;  // spareContacts_'s, at the same index
  std::vector<Piece> pieces_;                  // the second piece's on, when pieces run at once
};

}  // namespace phys
