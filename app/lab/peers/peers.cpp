// peerEngines() and runPeer(): the part of the peers that does not depend on any engine. It
// reads the scene once (peer_scene.cpp), builds it in the engine asked for, and steps it
// through the lab's one step loop (runner.h), as `lab compare` steps ours: each step timed alone.
#include <algorithm>
#include <exception>
#include <stdexcept>

#include "peer.h"
#include "peer_scene.h"
#include "runner.h"
#include "text.h"

namespace lab {
namespace {

// A peer engine as the runner steps it: its bodies in the description's order.
class PeerStepper final : public Stepper {
 public:
  PeerStepper(peers::Engine& engine, int bodies) : engine_(engine), bodies_(bodies) {}
  void step() override { engine_.step(); }
  void afterStep(int step) override { engine_.afterStep(step); }
  std::vector<phys::Vec3> positions() const override { return each(&peers::Engine::position); }
  std::vector<phys::Quat> orientations() const override { return each(&peers::Engine::orientation); }

 private:
  template <typename T>
  std::vector<T> each(T (peers::Engine::*read)(int) const) const {
    std::vector<T> out;
    out.reserve(static_cast<std::size_t>(bodies_));
    for (int i = 0; i < bodies_; ++i) out.push_back((engine_.*read)(i));
    return out;
  }

  peers::Engine& engine_;
  int bodies_;
};

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

std::string joined(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& p : parts) {
    if (p.empty()) continue;
    if (!out.empty()) out += "; ";
    out += p;
  }
  return out;
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
    result.unsupported = joined({joined(description.notes), std::string(e.what()) + ": not run"});
    return result;
  }
  result.settings = built->settings;

  PeerStepper stepper(*built, static_cast<int>(description.bodies.size()));
  RunSpec spec;
  spec.steps = steps;
  spec.checkpoints = checkpoints;
  spec.orientations = true;
  spec.stepTimes = true;
  RunRecord run;
  try {
    run = runSteps(stepper, spec);
  } catch (const std::exception& e) {
    // An engine that gives up part way (MuJoCo's errors arrive as exceptions) has no run to
    // compare; say so rather than report half of one.
    result.unsupported =
        joined({joined(description.notes), joined(built->notes), std::string(e.what()) + ": run stopped"});
    return result;
  }
  result.positions = std::move(run.positions);
  result.orientations = std::move(run.orientations);

  built->finish();
  result.maxPenetration = peers::groundPenetration(description, stepper.positions(), stepper.orientations());
  result.dropped = built->dropped;
  result.meanMsPerStep = steps > 0 ? run.steppingMs / steps : 0.0;
  result.medianMsPerStep = median(std::move(run.stepMs));
  result.unsupported = joined({joined(description.notes), joined(built->notes)});
  result.ran = true;
  return result;
}

}  // namespace lab
