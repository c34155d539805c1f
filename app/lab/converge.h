#pragma once
// lab converge (docs/lab.md, "lab converge"): how a run's error shrinks with the substep size h =
// dt / substeps, for every method and model, on scenes with an exact answer: analytic positions
// (<expect kind="position">) or, for free bodies in zero gravity, Euler's equations integrated by
// the lab's own code (free_body.h). convergeMain (commands.h) is the command; the pieces are here
// for the tests and for lab report.
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "charts.h"
#include "physics/settings.h"
#include "scenes/scene.h"

namespace lab {

/// The scenes `lab converge` studies when given none.
inline const std::vector<std::string> kConvergeScenes{"projectile", "pendulum-exact", "circular-orbit",
                                                      "tumbling-box"};
/// Substep counts tried when --substeps is not given: h halves from dt to dt / 64.
inline const std::vector<int> kConvergeSubsteps{1, 2, 4, 8, 16, 32, 64};
/// Relaxation passes per substep unless --iterations says otherwise.
inline constexpr int kConvergeIterations = 4;
/// A free-body scene's horizon unless --time says otherwise, unit: s; its error is measured at
/// four times spread evenly over it.
inline constexpr double kConvergeTime = 4.0;
/// Errors below this are round-off: left out of the fitted order. Verlet's velocity is a
/// difference of positions, so its round-off grows with the number of substeps: projectile.xml,
/// exact for every method, reads 1e-12 m at 1 substep and 8e-9 m at 64 (over 2 s); the free-body
/// reference is good to 1e-13 m. unit: m
inline constexpr double kConvergeFloor = 1.0e-8;
/// The order is fitted over this many of a line's finest points above the floor: where the error
/// has settled into its asymptotic power of h.
inline constexpr int kOrderPoints = 3;

/// One run: a method and model at one substep count.
struct ConvergeRow {
  std::string scene;
  std::string method;  ///< gauss-seidel, jacobi, xpbd, shake
  std::string model;   ///< corners, tetra, rigid; "particle" for a scene of particles alone
  int substeps = 1;
  double h = 0.0;  ///< unit: s; dt / substeps
  double error =
      0.0;  ///< unit: m; largest distance from the exact answer over the checkpoints; inf if it blew up
};

/// What `lab converge` does.
struct ConvergeOptions {
  std::vector<std::string> scenes;  ///< names or files; empty: kConvergeScenes
  std::vector<phys::SolverMethod> methods{phys::SolverMethod::GaussSeidel, phys::SolverMethod::Jacobi,
                                          phys::SolverMethod::Xpbd, phys::SolverMethod::Shake};
  std::vector<std::string> models;                ///< model labels; empty: every one a scene takes
  std::vector<int> substeps = kConvergeSubsteps;  ///< ascending or not; h = dt / each
  int iterations = kConvergeIterations;
  std::optional<double> time;  ///< unit: s; free-body scenes only; kConvergeTime when not given
  std::optional<std::filesystem::path> out;
  std::filesystem::path dataDir;  ///< holds assets/; empty: the build's default
};

/// What one scene is measured against, in one line for the table's heading.
struct ConvergeTarget {
  std::string kind;         ///< "analytic" or "free body"
  std::string description;  ///< what and when
};

/// Every run of one scene file under the options (its own dt), and what they were compared
/// with. Throws scenes::LoadError for the file, std::invalid_argument naming the scene when it
/// has no exact answer (no analytic positions, and not free bodies in zero gravity) or when its
/// free bodies touch something during a run.
std::vector<ConvergeRow> runConverge(const std::filesystem::path& file, const ConvergeOptions& options,
                                     ConvergeTarget& target, std::ostream* progress = nullptr);
/// The same for a file read before (`source`) and loaded as it is (`own`): nothing is read again.
std::vector<ConvergeRow> runConverge(const scenes::SceneSource& source, const scenes::Scene& own,
                                     const ConvergeOptions& options, ConvergeTarget& target,
                                     std::ostream* progress = nullptr);

/// The slope of log(error) against log(h) by least squares over the finest kOrderPoints points
/// of one line whose errors are finite and above kConvergeFloor; nullopt with fewer than two
/// such points (an exact method, or one that never came near).
std::optional<double> fittedOrder(const std::vector<ConvergeRow>& line);

/// The rows grouped into lines, one per scene, method and model, in first-seen order.
std::vector<std::vector<ConvergeRow>> convergeLines(const std::vector<ConvergeRow>& rows);

/// converge.csv: scene,method,model,substeps,h,error,blew_up.
std::string convergeCsv(const std::vector<ConvergeRow>& rows);
/// The table `lab converge` prints for one scene: a line per method and model, its error at each
/// substep count and its fitted order.
std::string convergeTable(const std::vector<ConvergeRow>& rows, const ConvergeTarget& target);
/// The scene's log-log chart, error against h, a line per method and model with its order in
/// the key; output "converge-SCENE".
Chart convergeChart(const std::vector<ConvergeRow>& rows);

}  // namespace lab
