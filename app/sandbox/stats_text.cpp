#include "stats_text.h"

#include <cmath>
#include <cstdio>

namespace sandbox {

std::string figure(const char* format, double value) {
  if (!std::isfinite(value)) return "overflow";
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

std::vector<StatsLine> statsLines(const phys::World& world) {
  const phys::Metrics m = world.metrics();
  std::vector<StatsLine> lines;
  lines.push_back({std::to_string(world.particles().size()) + " particles, " +
                   std::to_string(world.sticks().size()) + " sticks, " + std::to_string(world.jointCount()) +
                   " joints"});
  lines.push_back({std::to_string(world.bodies().size()) + " bodies, " + std::to_string(m.contacts) +
                   " contacts, " + std::to_string(world.broadPhasePairs()) + " broad-phase pairs"});
  const phys::Islands& islands = world.islands();
  const std::size_t count = islands.islandCount();
  lines.push_back({std::to_string(count) + (count == 1 ? " island (" : " islands (") +
                   std::to_string(islands.sleepingIslands()) + " asleep), bodies " +
                   std::to_string(islands.awakeBodies()) + " awake, " +
                   std::to_string(islands.sleepingBodies()) + " asleep"});
  lines.push_back({"stick error max " + figure("%.2e", m.maxConstraintError) + " rms " +
                   figure("%.2e", m.rmsConstraintError)});
  lines.push_back({"joint gap " + figure("%.2e", m.maxJointError) + " m, penetration " +
                   figure("%.2e", m.maxPenetration) + " m"});
  if (world.solverSettings().jointProjection.enabled && !world.rigidJoints().empty()) {
    const phys::JointProjectionReport& p = world.lastJointProjection();
    lines.push_back({"joint projection: " + std::to_string(p.iterations) +
                     " solves in the last step, widest " + figure("%.2e", p.errorBefore) + " before, " +
                     figure("%.2e", p.errorAfter) + " after"});
  }
  lines.push_back({"energy " + figure("%.3f", m.energy()) + " J (kinetic " + figure("%.3f", m.kineticEnergy) +
                   "), max speed " + figure("%.2f", m.maxSpeed) + " m/s"});
  if (m.frozen > 0) {
    const phys::FreezeReport& last = world.freezes().back();
    lines.push_back({"frozen: " + std::to_string(world.freezes().size()) + " bodies (" +
                         std::to_string(m.frozen) + " particles); last " + last.name + ": " + last.reason +
                         " at " + figure("%.2f", last.time) + " s",
                     true});
  } else {
    lines.push_back({"frozen: none"});
  }
  return lines;
}

}  // namespace sandbox
