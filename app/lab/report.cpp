#include "report.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string_view>
#include <system_error>

#include "csv.h"

namespace lab {
namespace {

// printf-style %.{digits}g, for the summary's rounded figures and the exact ones of JSON. A
// figure that overflowed (the guard froze the world under a gravity of 1e308, say) reads n/a,
// never inf or nan.
std::string num(double value, int digits = 6) {
  if (!std::isfinite(value)) return "n/a";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

// "1 substep" but "3 substeps".
std::string count(std::size_t n, const char* singular, const char* plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

// A stage's summed time and its share of the summed step totals, in aligned columns.
std::string stageLine(std::string_view name, double ms, double totalMs) {
  std::string s(name);
  s.resize(std::max<std::size_t>(s.size(), 14), ' ');
  s += num(ms, 4) + " ms";
  if (totalMs > 0.0) s += " (" + num(100.0 * ms / totalMs, 3) + "%)";
  return s + "\n";
}

// Summaries stay readable when the guard froze thousands of particles.
constexpr std::size_t kMaxFreezesListed = 10;

}  // namespace

std::string jsonNumber(double value) {
  return std::isfinite(value) ? num(value, 17) : "null";
}

std::string jsonString(std::string_view text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      out += buffer;
    } else {
      out += c;  // UTF-8 passes through as it is
    }
  }
  return out + "\"";
}

std::string hexHash(std::uint64_t hash) {
  char buffer[24];
  std::snprintf(buffer, sizeof buffer, "%016" PRIx64, hash);
  return buffer;
}

std::string jsonText(const RunResult& r) {
  const phys::Metrics& m = r.final;
  std::string s = "{";
  // Keys in the order docs/lab.md lists them; values already in their JSON form.
  auto field = [&](const char* key, const std::string& value) {
    s += s.size() > 1 ? ",\"" : "\"";
    s += key;
    s += "\":";
    s += value;
  };
  field("scene", jsonString(r.scene));
  field("method", jsonString(phys::toString(r.solver.method)));
  field("iterations", std::to_string(r.solver.iterations));
  field("substeps", std::to_string(r.solver.substeps));
  field("dt", jsonNumber(r.solver.dt));
  field("steps", std::to_string(r.steps));
  field("particles", std::to_string(r.particles));
  field("constraints", std::to_string(r.constraints));
  field("bodies", std::to_string(r.bodies));
  field("contacts", std::to_string(m.contacts));
  field("ms_per_step", jsonNumber(r.msPerStep));
  field("max_constraint_error", jsonNumber(m.maxConstraintError));
  field("rms_constraint_error", jsonNumber(m.rmsConstraintError));
  field("max_joint_error", jsonNumber(m.maxJointError));
  field("max_penetration", jsonNumber(m.maxPenetration));
  field("max_speed", jsonNumber(m.maxSpeed));
  field("energy_initial", jsonNumber(r.energyInitial));
  field("energy_final", jsonNumber(m.energy()));
  field("frozen", std::to_string(m.frozen));
  field("islands", std::to_string(r.islands));
  field("awake_bodies", std::to_string(r.awakeBodies));
  field("sleeping_bodies", std::to_string(r.sleepingBodies));
  field("hash", jsonString(hexHash(r.hash)));
  return s + "}\n";
}

std::string summaryText(const RunResult& r) {
  const phys::Metrics& m = r.final;
  const phys::Profile& p = r.stageSums;
  std::string s;
  s += "scene        " + r.scene + (r.file.empty() ? "" : " (" + r.file.string() + ")") + "\n";
  s +=
      "solver       " + std::string(phys::toString(r.solver.method)) +
      (r.xpbdAlone ? " (no stick to relax: every method steps this world alike, rigid bodies by XPBD)" : "") +
      ", " + count(static_cast<std::size_t>(r.solver.iterations), "iteration", "iterations") + ", " +
      count(static_cast<std::size_t>(r.solver.substeps), "substep", "substeps") + ", dt " + num(r.solver.dt) +
      " s\n";
  s += "world        " + count(r.particles, "particle", "particles") + ", " +
       count(r.constraints, "constraint", "constraints") + ", " + count(r.bodies, "box", "boxes") + "\n";
  s += "islands      " + std::to_string(r.islands) + " at the end, " + std::to_string(r.awakeBodies) +
       " bodies awake, " + std::to_string(r.sleepingBodies) + " asleep" +
       (r.solver.sleep.enabled ? "" : " (sleep off)") + "\n";
  s += "ran          " + count(static_cast<std::size_t>(r.steps), "step", "steps") + ", " +
       num(r.simulatedTime) + " s simulated, in " + num(r.wallMs, 4) + " ms wall: " + num(r.msPerStep, 4) +
       " ms/step\n";
  // Profile::total is the physics' own clock per step; the wall time above also holds the
  // loop around it. The median shrugs off the odd step the scheduler interrupted.
  s += "step time    median " + num(r.medianStepMs, 4) + " ms (the physics' own Profile::total)\n";
  // One line per stage, in the step's order, then what the stages leave of the total: the
  // step's own bookkeeping and clock reads.
  s += "stages       summed over the run, and their share of the steps' total:\n";
  for (std::size_t i = 0; i < phys::kStageCount; ++i) {
    const auto stage = static_cast<phys::Stage>(i);
    s += "             " + stageLine(phys::toString(stage), p[stage], p.total);
  }
  s += "             " + stageLine("other", p.total - p.staged(), p.total);
  s += "contacts     " + std::to_string(m.contacts) + " in the last step, max penetration " +
       num(m.maxPenetration) + " m\n";
  s += "constraints  error max " + num(m.maxConstraintError) + ", rms " + num(m.rmsConstraintError) +
       " (of rest length)\n";
  if (r.joints > 0)
    s += "joints       " + count(r.joints, "link", "links") + ", max error " + num(m.maxJointError) + " m\n";
  s += "speed        max " + num(m.maxSpeed) + " m/s\n";
  s += "energy       initial " + num(r.energyInitial) + " J, final " + num(m.energy()) + " J (change " +
       num(m.energy() - r.energyInitial) + " J)\n";
  if (r.freezes.empty()) {
    s += "frozen       none\n";
  } else {
    s += "frozen       " + count(static_cast<std::size_t>(m.frozen), "particle", "particles") + " in " +
         count(r.freezes.size(), "report", "reports") + "\n";
    for (std::size_t i = 0; i < r.freezes.size() && i < kMaxFreezesListed; ++i) {
      const phys::FreezeReport& f = r.freezes[i];
      s += "  t=" + num(f.time) + " s  " + f.name + ": " + f.reason + "\n";
    }
    if (r.freezes.size() > kMaxFreezesListed) {
      s += "  ... and " + std::to_string(r.freezes.size() - kMaxFreezesListed) + " more\n";
    }
  }
  s += "hash         " + hexHash(r.hash) + "\n";
  return s;
}

std::string dumpCsv(const phys::World& world, std::span<const scenes::NamedBody> bodies) {
  std::string s = "name,x,y,z,qw,qx,qy,qz\n";
  for (const scenes::NamedBody& b : bodies) {
    phys::BodyPose pose;  // a particle keeps the identity orientation
    if (b.kind == scenes::NamedBody::Kind::Body) {
      pose = world.bodyPose(b.body());
    } else {
      pose.center = world.particles().position.at(b.index);
    }
    const phys::Vec3& c = pose.center;
    const phys::Quat& q = pose.orientation;
    s += csvField(b.name);
    // Appended piecewise: GCC 12 warns falsely (-Wrestrict) about "," + std::string here.
    for (double v : {c.x, c.y, c.z, q.w, q.x, q.y, q.z}) {
      s += ',';
      s += csvNumber(v, 17);
    }
    s += "\n";
  }
  return s;
}

}  // namespace lab
