#include "report.h"

#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <span>
#include <sstream>
#include <string_view>

#include "csv.h"
#include "json.h"
#include "run.h"
#include "text.h"

namespace lab {
namespace {

// A stage's summed time and its share of the summed step totals, in aligned columns.
std::string stageLine(std::string_view name, double ms, double totalMs) {
  std::string s =
      printed("%-14.*s", static_cast<int>(name.size()), name.data()) + formatNumber(ms, 4) + " ms";
  if (totalMs > 0.0) s += " (" + formatNumber(100.0 * ms / totalMs, 3) + "%)";
  return s + "\n";
}

// Summaries stay readable when the guard froze thousands of particles.
constexpr std::size_t kMaxFreezesListed = 10;

}  // namespace

std::string hexHash(std::uint64_t hash) {
  return printed("%016" PRIx64, hash);
}

std::string jsonText(const RunResult& r) {
  const phys::Metrics& m = r.final;
  // Keys in the order docs/lab.md lists them.
  Json j;
  j["scene"] = r.scene;
  j["method"] = phys::toString(r.solver.method);
  j["iterations"] = r.solver.iterations;
  j["substeps"] = r.solver.substeps;
  j["dt"] = r.solver.dt;
  j["joint_projection"] = r.solver.jointProjection.enabled;
  j["threads"] = r.solver.threads;
  j["sleep"] = r.solver.sleep.enabled;
  j["steps"] = r.steps;
  j["particles"] = r.particles;
  j["constraints"] = r.constraints;
  j["bodies"] = r.bodies;
  j["contacts"] = m.contacts;
  j["ms_per_step"] = r.msPerStep;
  j["max_constraint_error"] = m.maxConstraintError;
  j["rms_constraint_error"] = m.rmsConstraintError;
  j["max_joint_error"] = m.maxJointError;
  j["max_penetration"] = m.maxPenetration;
  j["max_speed"] = m.maxSpeed;
  // The worst after any step, where the keys above are the last step's.
  for (std::size_t i = 0; i < kRunMetricCount; ++i)
    j[std::string(kRunMetrics[i].column) + "_over_run"] = r.worst[i];
  j["energy_initial"] = r.energyInitial;
  j["energy_final"] = m.energy();
  j["frozen"] = m.frozen;
  j["islands"] = r.islands;
  j["largest_island"] = r.largestIsland;
  j["awake_bodies"] = r.awakeBodies;
  j["sleeping_bodies"] = r.sleepingBodies;
  j["hash"] = hexHash(r.hash);
  Json drives = Json::array();
  for (const DriveFigures& d : r.drives) {
    drives.push_back(Json{{"character", d.character},
                          {"bone", d.bone},
                          {"root", d.root},
                          {"rms_torque", d.rmsTorque},
                          {"peak_torque", d.peakTorque},
                          {"rms_force", d.rmsForce},
                          {"peak_force", d.peakForce}});
  }
  if (!r.drives.empty()) j["drives"] = drives;  // with characters alone: the object stays flat without
  return jsonLine(j);
}

// What a character's drives came to when some figure of theirs is not finite, as every figure of
// the lab says it: a drive that ran away to infinity blew up, and one that is no number is n/a.
// Empty when every figure is finite.
std::string unfiniteDrives(std::span<const DriveFigures> parts) {
  bool notANumber = false;
  for (const DriveFigures& d : parts) {
    for (const double v : {d.rmsTorque, d.peakTorque, d.rmsForce, d.peakForce}) {
      if (std::isinf(v)) return kBlewUp;
      notANumber = notANumber || std::isnan(v);
    }
  }
  return notANumber ? "n/a" : "";
}

// A line per character: what each part's drive needed to follow the clip, RMS over the run and
// peak ("head 3.1/12"), the root's hand of god first as a force and a torque. A character whose
// figures are not all finite reads "blew up" (or "n/a") once, not part by part ("blew up/blew up").
std::string drivesText(const std::vector<DriveFigures>& drives) {
  if (drives.empty()) return {};
  std::string s =
      "drives       what each character's parts needed to follow its clip, RMS/peak over the run:\n";
  for (std::size_t first = 0, end = 0; first < drives.size(); first = end) {
    end = first + 1;
    while (end < drives.size() && drives[end].character == drives[first].character) ++end;
    const std::span<const DriveFigures> parts(drives.data() + first, end - first);
    s += "             " + drives[first].character + ":";
    if (const std::string words = unfiniteDrives(parts); !words.empty()) {
      s += " " + words + "\n";
      continue;
    }
    for (std::size_t i = 0; i < parts.size(); ++i) {
      const DriveFigures& d = parts[i];
      if (d.root) {
        s += " " + d.bone + " (root) " + formatNumber(d.rmsForce, 3) + "/" + formatNumber(d.peakForce, 3) +
             " N and " + formatNumber(d.rmsTorque, 3) + "/" + formatNumber(d.peakTorque, 3) + " N m;";
      } else {
        s += std::string(i == 0 || parts[i - 1].root ? " " : ", ") + d.bone + " " +
             formatNumber(d.rmsTorque, 3) + "/" + formatNumber(d.peakTorque, 3);
      }
    }
    s += " N m\n";
  }
  return s;
}

std::string summaryText(const RunResult& r) {
  const phys::Metrics& m = r.final;
  const phys::Profile& p = r.stageSums;
  std::string s;
  s += "scene        " + r.scene + (r.file.empty() ? "" : " (" + r.file.string() + ")") + "\n";
  s +=
      "solver       " + std::string(phys::toString(r.solver.method)) +
      (r.xpbdAlone ? " (no stick to relax: every method steps this world alike, rigid bodies by XPBD)" : "") +
      ", " + ixsWords(r.solver.iterations, r.solver.substeps, ", ") + ", dt " + formatNumber(r.solver.dt) +
      " s" + (r.solver.jointProjection.enabled ? ", rigid joints projected" : "") + "\n";
  s += "world        " + count(r.particles, "particle", "particles") + ", " +
       count(r.constraints, "constraint", "constraints") + ", " + count(r.bodies, "box", "boxes") + "\n";
  s += "islands      " + std::to_string(r.islands) + " at the end, " +
       (r.largestIsland > 0 ? "the largest of " + count(r.largestIsland, "body", "bodies") + ", " : "") +
       std::to_string(r.awakeBodies) + " bodies awake, " + std::to_string(r.sleepingBodies) + " asleep" +
       (r.solver.sleep.enabled ? "" : " (sleep off)") + "\n";
  s += "ran          " + count(static_cast<std::size_t>(r.steps), "step", "steps") + ", " +
       formatNumber(r.simulatedTime) + " s simulated, on " +
       count(static_cast<std::size_t>(r.solver.threads), "thread", "threads") + ", in " +
       formatNumber(r.wallMs, 4) + " ms wall: " + formatNumber(r.msPerStep, 4) + " ms/step\n";
  // Profile::total is the physics' own clock per step; the wall time above is the calls to
  // World::step() as the lab sees them. The median shrugs off the odd step the scheduler interrupted.
  s += "step time    median " + formatNumber(r.medianStepMs, 4) + " ms (the physics' own Profile::total)\n";
  // One line per stage, in the step's order, then what the stages leave of the total: the
  // step's own bookkeeping and clock reads.
  s += "stages       summed over the run, and their share of the steps' total:\n";
  for (std::size_t i = 0; i < phys::kStageCount; ++i) {
    const auto stage = static_cast<phys::Stage>(i);
    s += "             " + stageLine(phys::toString(stage), p[stage], p.total);
  }
  s += "             " + stageLine("other", p.total - p.staged(), p.total);
  s += "contacts     " + std::to_string(m.contacts) + " in the last step, max penetration " +
       formatFigure(m.maxPenetration, " m") + "\n";
  s += "constraints  error max " + formatNumber(m.maxConstraintError) + ", rms " +
       formatNumber(m.rmsConstraintError) + " (of rest length)\n";
  if (r.joints > 0)
    s += "joints       " + count(r.joints, "link", "links") + ", max error " +
         formatFigure(m.maxJointError, " m") + "\n";
  s += "speed        max " + formatFigure(m.maxSpeed, " m/s") + "\n";
  s += "worst        after any step:";
  for (std::size_t i = 0; i < kRunMetricCount; ++i) {
    const RunMetric& metric = kRunMetrics[i];
    s += std::string(i == 0 ? " " : ", ") + metric.name + " " + formatFigure(r.worst[i], metric.unitAfter()) +
         (metric.over == OverRun::Rms ? " (RMS over the run)" : "");
  }
  s += "\n";
  s += drivesText(r.drives);
  s += "energy       initial " + formatFigure(r.energyInitial, " J") + ", final " +
       formatFigure(m.energy(), " J") + " (change " + formatFigure(m.energy() - r.energyInitial, " J") +
       ")\n";
  if (r.freezes.empty()) {
    s += "frozen       none\n";
  } else {
    s += "frozen       " + count(static_cast<std::size_t>(m.frozen), "particle", "particles") + " in " +
         count(r.freezes.size(), "report", "reports") + "\n";
    for (std::size_t i = 0; i < r.freezes.size() && i < kMaxFreezesListed; ++i) {
      const phys::FreezeReport& f = r.freezes[i];
      s += "  t=" + formatNumber(f.time) + " s  " + f.name + ": " + f.reason + "\n";
    }
    if (r.freezes.size() > kMaxFreezesListed) {
      s += "  ... and " + std::to_string(r.freezes.size() - kMaxFreezesListed) + " more\n";
    }
  }
  s += "hash         " + hexHash(r.hash) + "\n";
  return s;
}

std::string drivesTable(const std::string& scene, const std::string& runJson) {
  const Json j = Json::parse(runJson);
  std::ostringstream md;
  md << "What each part's drive needed over the run's " << j["steps"].get<int>() << " steps ("
     << formatNumber(j["steps"].get<int>() * j["dt"].get<double>(), 3) << " s) at the scene's own setting ("
     << j["method"].get<std::string>() << " " << ixs(j["iterations"].get<int>(), j["substeps"].get<int>())
     << ", `lab run " << scene
     << " --json`'s `drives`): the torque from its parent's joint, and for the root part the hand of god's "
        "force and torque, RMS over the run's steps and the largest after any step.\n\n"
        "| part | RMS | peak |\n|---|---:|---:|\n";
  for (const Json& d : j.value("drives", Json::array())) {  // a run without drives has none
    // jsonText writes a figure that is not finite as null: a drive of a run that blew up.
    const auto figure = [&](const std::string& key, const std::string& unit) {
      const Json& v = d[key];
      return v.is_null() ? std::string(kBlewUp) : formatFigure(v.get<double>(), unit, 3);
    };
    const bool root = d["root"].get<bool>();
    const auto cell = [&](const std::string& which) {  // "rms" or "peak"; the root's has the force too
      return (root ? figure(which + "_force", " N") + ", " : "") + figure(which + "_torque", " N m");
    };
    md << "| " << d["bone"].get<std::string>() << (root ? " (root: hand of god)" : "") << " | " << cell("rms")
       << " | " << cell("peak") << " |\n";
  }
  return md.str();
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
    std::vector<std::string> fields{csvField(b.name)};
    for (double v : {c.x, c.y, c.z, q.w, q.x, q.y, q.z}) fields.push_back(csvNumber(v, 17));
    s += csvLine(fields);
  }
  return s;
}

}  // namespace lab
