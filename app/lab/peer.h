#pragma once
// Peer engines, built into the lab when CMake finds them (option LAB_PEERS, on by default;
// scripts/install-deps installs libbullet-dev, libode-dev and libmujoco-dev). Each adapter
// builds the same scene from our loaded world: the ground, one rigid body per body of
// bodies.h (a box for each box, a capsule for each capsule, a small sphere for each loose
// particle) with the same mass, size, pose, velocity and friction, and joints for what joins
// them, then steps it with the engine's default solver at our dt. docs/lab.md, "lab compare and the peers",
// lists what each engine can and cannot express.
#include <string>
#include <string_view>
#include <vector>

#include "physics/types.h"
#include "scenes/scene.h"

namespace lab {

struct PeerResult {
  std::string engine;  ///< "bullet", "ode" or "mujoco"
  /// Empty when the engine expressed the whole scene; else what it could not (the run is then
  /// not made, or made without it, as the text says).
  std::string unsupported;
  bool ran = false;  ///< false when the scene could not be expressed at all
  /// The engine's version, solver and settings as run, one line for tables.
  std::string settings;
  /// unit: ms; the steps' summed wall time over their number: the cost of a step, spikes
  /// included, as lab sweep and compare time ours (timeSetting)
  double meanMsPerStep = 0.0;
  /// Per checkpoint asked for, bodyPositions() order: where the engine's bodies are.
  std::vector<std::vector<phys::Vec3>> positions;
  /// The same bodies' orientations at the same checkpoints: with the positions, the poses that
  /// the lab measures penetration, joint gaps and flips from (peers/pose_measures.h), the same
  /// way for every engine.
  std::vector<std::vector<phys::Quat>> orientations;
  double maxPenetration = 0.0;  ///< unit: m; deepest body below the ground at the end
  /// True when the engine dropped contacts or constraints for want of the room it allocated up
  /// front (peers::Engine::dropped): what it did is then not its solver's (`unsupported` says).
  bool dropped = false;
};

/// The engines built in, in a fixed order; empty when the lab was built without peers.
std::vector<std::string> peerEngines();

/// Builds `scene` (as loaded, not yet stepped) in the engine and steps it `steps` times at
/// `dt`, recording the bodies' positions after each checkpoint step (ascending, <= steps).
/// `sleep`: whether an engine that can put resting bodies to sleep may (peers::Description::sleep);
/// not unless asked, as ours do not (docs/physics.md, "Islands and sleeping").
PeerResult runPeer(std::string_view engine, const scenes::Scene& scene, double dt, int steps,
                   const std::vector<int>& checkpoints, bool sleep = false);

}  // namespace lab
