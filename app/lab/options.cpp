#include "options.h"

namespace lab {

void describeRun(CommandLine& line, RunOptions& o) {
  line.about(
      "Steps one scene and prints what it measured: the cost of each stage, the errors, the\n"
      "energy, and what the guard froze.");
  line.scene(o.scene);
  line.option(option::kSteps, o.steps, "(default 600)");
  line.option(option::kDt, o.dt, "(default: the scene's)");
  line.option(option::kMethods, o.method, "(default: the scene's)");
  line.option(option::kIterations, o.iterations, "(default: the scene's)");
  line.option(option::kSubsteps, o.substeps, "(default: the scene's)");
  line.option(option::kModels, o.model,
              "(rigid on ragdolls too; a rigid body is solved by XPBD whatever the method)");
  line.option(option::kSleep, o.sleep, "(default off, whatever the scene says)");
  line.option(option::kJointProjection, o.jointProjection, "(default: the scene's)");
  line.option(option::kThreads, o.threads, "(default: the scene's, else 1)");
  line.flag(option::kJson, o.json, true, "one object instead of the summary");
  line.option(option::kDump, o.dump, "");
  line.existingFolder(option::kData, o.dataDir, "");
}

}  // namespace lab
