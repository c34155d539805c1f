// peerEngines() and runPeer(): the part of the peers that does not depend on any engine. It
// reads the scene once (peer_scene.cpp), builds it in the engine asked for, and steps it
// through the lab's one step loop (runner.h), as `lab compare` steps ours: each step timed alone.
#include <exception>

#include "peer.h"
#include "peer_scene.h"
#include "runner.h"
#include "text.h"

namespace lab {
namespace {

// The adapters built in, in the fixed order the tables use.
struct Adapter {
  const char* name;
  std::unique_ptr<peers::Engine> (*make)(const peers::Description&, double);
};
constexpr Adapter kAdapters[] = {
#ifdef LAB_PEER_BULLET
    {"bullet", &peers::makeBullet},
#endif
#ifdef LAB_PEER_ODE
    {"ode", &peers::makeOde},
#endif
#ifdef LAB_PEER_MUJOCO
    {"mujoco", &peers::makeMujoco},
#endif
    {nullptr, nullptr},  // keeps the array non-empty when no adapter is built
};

const Adapter* findAdapter(std::string_view name) {
  for (const Adapter& a : kAdapters) {
    if (a.name != nullptr && name == a.name) return &a;
  }
  return nullptr;
}

// What a run left out or showed, for the table: the scene's notes, the engine's, and then why
// it stopped when it did.
std::string notesOf(const peers::Description& description, const peers::Engine* engine,
                    const std::string& stopped = {}) {
  std::vector<std::string> parts = description.notes;
  if (engine != nullptr) parts.insert(parts.end(), engine->notes.begin(), engine->notes.end());
  if (!stopped.empty()) parts.push_back(stopped);
  return join(parts, "; ");
}

}  // namespace

std::unique_ptr<peers::Engine> peers::makeEngine(std::string_view name, const Description& scene, double dt) {
#ifdef LAB_PEER_MUJOCO
  if (name == "mujoco-tree") return makeMujocoTree(scene, dt);  // the tests' way to the tree form
#endif
  const Adapter* adapter = findAdapter(name);
  return adapter != nullptr ? adapter->make(scene, dt) : nullptr;
}

std::vector<std::string> peerEngines() {
  std::vector<std::string> names;
  for (const Adapter& a : kAdapters) {
    if (a.name != nullptr) names.emplace_back(a.name);
  }
  return names;
}

PeerResult runPeer(std::string_view engine, const scenes::Scene& scene, double dt, int steps,
                   const std::vector<int>& checkpoints, bool sleep) {
  PeerResult result;
  result.engine = std::string(engine);
  const Adapter* adapter = findAdapter(engine);
  if (adapter == nullptr) {
    result.unsupported = "not built into this lab";
    return result;
  }

  peers::Description description = peers::describe(scene);
  description.sleep = sleep;
  if (!description.refused.empty()) {
    result.unsupported = description.refused + " not expressed: not run";
    return result;
  }

  std::unique_ptr<peers::Engine> built;
  try {
    built = adapter->make(description, dt);
  } catch (const std::exception& e) {
    result.unsupported = notesOf(description, nullptr, std::string(e.what()) + ": not run");
    return result;
  }
  result.settings = built->settings;

  RunRecord run;
  try {
    run = runSteps(*built, {.steps = steps, .checkpoints = checkpoints, .orientations = true});
  } catch (const std::exception& e) {
    // An engine that gives up part way (MuJoCo's errors arrive as exceptions) has no run to
    // compare; say so rather than report half of one.
    result.unsupported = notesOf(description, built.get(), std::string(e.what()) + ": run stopped");
    return result;
  }
  result.positions = std::move(run.positions);
  result.orientations = std::move(run.orientations);

  built->finish();
  result.maxPenetration = peers::groundPenetration(description, built->positions(), built->orientations());
  result.dropped = built->dropped;
  result.meanMsPerStep = steps > 0 ? run.steppingMs / steps : 0.0;
  result.unsupported = notesOf(description, built.get());
  result.ran = true;
  return result;
}

}  // namespace lab
