#include "options.h"

namespace lab {

void describeRun(CommandLine& line, RunOptions& o) {
  line.scene(o.scene);
  line.count(option::kSteps, kMaxSteps, o.steps, "(default 600)");
  line.dt(o.dt, "(default: the scene's)");
  line.method(o.method, "(default: the scene's)");
  line.count(option::kIterations, phys::kMaxIterations, o.iterations, "(default: the scene's)");
  line.count(option::kSubsteps, phys::kMaxSubsteps, o.substeps, "(default: the scene's)");
  line.model(o.model, "(rigid on ragdolls too; a rigid body is solved by XPBD whatever the method)");
  line.onOff(option::kSleep, o.sleep, "(default off, whatever the scene says)");
  line.onOff(option::kJointProjection, o.jointProjection, "(default: the scene's)");
  line.count(option::kThreads, phys::kMaxThreads, o.threads, "(default: the scene's, else 1)");
  line.flag(option::kJson, o.json, true, "one object instead of the summary");
  line.file(option::kDump, o.dump, "");
  line.folder(option::kData, o.dataDir, "");
}

std::string parseRun(const std::vector<std::string>& args, RunOptions& o) {
  CommandLine line("run", "");
  describeRun(line, o);
  return line.parse(args);
}

}  // namespace lab
