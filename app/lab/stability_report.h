#pragma once
// What `lab stability` writes: the markdown report (stdout and stability.md), the CSV, and
// the gnuplot script and matrices of the two heat maps (docs/lab.md, "lab stability").
#include <string>
#include <vector>

#include "stability_run.h"

namespace lab::stability {

/// The whole suite's results: outcomes[scene][column], the settings' columns first (in the
/// order of `settings`), then one per peer (in the order of `peers`).
struct SuiteResult {
  std::vector<SuiteScene> scenes;
  std::vector<Setting> settings;
  /// the blocks of `settings` (settingGroup: a method, and a model when --models gave one), in order
  std::vector<std::string> methods;
  std::vector<std::string> peers;
  std::string peerNote;  ///< why there are no peer columns ("--no-peers", none built), or ""
  std::vector<std::vector<Outcome>> outcomes;
  double seconds = 0.0;    ///< unit: s; the whole run, wall clock
  int jobs = 1;            ///< our runs at a time (--jobs); above 1 the timings are of shared cores
  bool wholeRuns = false;  ///< --whole-runs: failing runs stepped to their end, not stopped once failed
};

/// The report: the passes per scene and method (peers beside them), then one grid per method
/// of value / limit per setting, then the peers' figures and notes.
std::string markdownReport(const SuiteResult& result);

/// scene,method,model,iterations,substeps,passed,blew_up,value,limit,ratio,criterion,ms_per_step,note:
/// one row per run (a peer's row has its engine as the method and no iterations or substeps).
std::string csvReport(const SuiteResult& result);

/// The heat maps' matrices (gnuplot's "matrix rowheaders columnheaders" form): pass is 1, fail
/// 0, not judged 0.5; error is log10(value / limit) clipped to [-3, 3], NaN when not judged.
std::string passMatrix(const SuiteResult& result);
std::string errorMatrix(const SuiteResult& result);

/// The gnuplot script drawing stability-pass.png/.svg and stability-error.png/.svg from
/// stability-pass.dat and stability-error.dat in its own folder.
std::string gnuplotScript(const SuiteResult& result);

/// A ratio for people: three significant digits, "inf" for a blow-up.
std::string formatRatio(double ratio);

}  // namespace lab::stability
