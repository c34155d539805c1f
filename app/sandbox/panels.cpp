#include "panels.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <imgui.h>
#include <imgui_stdlib.h>

#include "controls.h"
#include "stats_text.h"
#include "text.h"  // the lab's setting label

namespace sandbox {
namespace {

constexpr float kColumnShare = 0.27f;                      // of the window's width: 345 pixels of 1280
constexpr float kColumnMin = 300.0f, kColumnMax = 440.0f;  // unit: pixels

// A section of the column: a header that folds, with a close button that hides it (the View menu
// shows it again). Reset layout opens it as it first was.
bool beginSection(const char* title, bool* shown, bool openAtFirst, bool reset) {
  if (!*shown) return false;
  ImGui::SetNextItemOpen(openAtFirst, reset ? ImGuiCond_Always : ImGuiCond_Once);
  return ImGui::CollapsingHeader(title, shown);
}

// A double edited through a float slider: written back only when the slider moved, so an
// untouched 9.81 never becomes 9.8100004 (the run would no longer match the lab's).
bool sliderReal(const char* label, double& value, float min, float max, const char* format = "%.3f",
                ImGuiSliderFlags flags = 0) {
  float v = static_cast<float>(value);
  if (!ImGui::SliderFloat(label, &v, min, max, format, flags)) return false;
  value = std::clamp(static_cast<double>(v), static_cast<double>(min), static_cast<double>(max));
  return true;
}

// A whole-number setting's slider: applied as it is dragged, but a typed number (Ctrl+click) only
// once the typing ends, so typing 100000 does not apply 1, 10, 100 and 1000 on the way. Typed
// values are clamped to the slider's range.
bool settingSlider(const char* label, int& value, int min, int max, UiState& ui) {
  const bool mine = ui.typing && ui.typing->first == label;
  int v = mine ? ui.typing->second : value;
  const bool moved = ImGui::SliderInt(label, &v, min, max, "%d", ImGuiSliderFlags_AlwaysClamp);
  if (ImGui::IsItemActive() && ImGui::GetIO().WantTextInput) {
    ui.typing = std::make_pair(std::string(label), v);
    return false;
  }
  if (mine && ImGui::IsItemDeactivated()) {
    const bool edited = ImGui::IsItemDeactivatedAfterEdit();
    ui.typing.reset();
    if (!edited) return false;
    value = std::clamp(v, min, max);
    return true;
  }
  if (!moved) return false;
  value = v;
  return true;
}

void settingsSection(Session& session, UiState& ui);

// TextDisabled's grey, wrapped at the column's edge.
void greyWrapped(const std::string& text) {
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
  ImGui::TextWrapped("%s", text.c_str());
  ImGui::PopStyleColor();
}

void overlaySection(Session& session, UiState& ui) {
  if (session.overlayActive()) ImGui::SetNextItemOpen(true, ImGuiCond_Once);  // started from the command line
  if (!ImGui::CollapsingHeader("Method overlay")) return;
  ImGui::TextWrapped(
      "2 to 4 runs of this world from its state now, e.g. iterations=3 / substeps=8,iterations=1 / "
      "method=xpbd");
  for (int i = 0; i < kMaxOverlayRuns; ++i) {
    ImGui::PushID(i);
    ImGui::ColorButton("##c", ImVec4(kRunColors[i].r, kRunColors[i].g, kRunColors[i].b, 1.0f), 0,
                       ImVec2(14, 14));
    ImGui::SameLine();
    ImGui::InputText("##spec", &ui.overlayText[static_cast<std::size_t>(i)]);
    ImGui::PopID();
  }
  if (ImGui::Button(session.overlayActive() ? "Restart overlay" : "Start overlay")) {
    std::vector<OverlaySpec> specs;
    std::string error;
    for (const std::string& text : ui.overlayText) {
      if (text.empty()) continue;
      const ParsedOverlaySpec parsed = parseOverlaySpec(text);
      if (!parsed.error.empty() && error.empty()) error = parsed.error;
      specs.push_back(parsed.spec);
    }
    if (error.empty()) error = session.startOverlay(specs);
    ui.message = error.empty() ? session.status() : "overlay: " + error;
  }
  if (session.overlayActive()) {
    ImGui::SameLine();
    if (ImGui::Button("Stop overlay")) {
      session.stopOverlay();
      ui.message = session.status();  // the status line said the overlay still ran
    }
  }
}

}  // namespace

void stepOnce(Session& session, UiState& ui) {
  ui.replaying = false;
  const Recording& r = session.recording();
  const long now = session.scene().world.stepCount();
  if (ui.paused && !session.dragging() && now < r.last() && r.covers(now)) {
    const std::string error = session.rewindTo(now + 1);
    ui.message = error.empty() ? session.status() : error;
  } else {
    ui.stepOnce = true;
  }
}

void togglePause(UiState& ui) {
  if (std::exchange(ui.replaying, false)) return;  // Play stops, paused where it was
  ui.paused = !ui.paused;
}

void applyRemembered(const UserSettings& user, const Options& options, UiState& ui) {
  ui.showSimulation = user.showSimulation;
  ui.showWorld = user.showWorld;
  ui.showDraw = user.showDraw;
  ui.showStats = user.showStats;
  ui.draw.mode = options.draw.value_or(parseDrawMode(user.drawMode).value_or(DrawMode::Filled));
  ui.draw.markers = options.markers || user.markers;
  ui.draw.trails = options.trails;
  ui.draw.targets = options.targets;
  ui.panelsHidden = options.hidePanels;
  ui.showRewind = user.showRewind;
  ui.showLab = user.showLab;
  if (options.unfold) ui.unfolded = *options.unfold;
  SectionFlags named = options.unfold.value_or(SectionFlags{});
  named[5] = named[5] || options.sweep;  // --sweep unfolds the Lab, for its progress and chart
  // A section the command line unfolds is shown, though the last run hid it (its close button).
  const auto shown = sectionsShown(ui);
  for (std::size_t i = 0; i < kSectionNames.size(); ++i) {
    if (named[i]) ui.unfolded[i] = *shown[i] = true;
  }
  ui.draw.coloring =
      options.coloring.value_or(parseBodyColoring(user.colorBy.value_or("")).value_or(BodyColoring::Body));
  if (user.throwSpeed) ui.throwSpeed = *user.throwSpeed;
  if (user.recordingBudgetMb) ui.recordingBudgetMb = *user.recordingBudgetMb;
  ui.draw.shadows = !options.noShadows;
  // The overlay the command line started, so that Restart runs the same settings; else examples.
  ui.overlayText = {"iterations=3", "substeps=8,iterations=1", "method=xpbd", ""};
  if (!options.overlay.empty()) {
    for (std::size_t i = 0; i < ui.overlayText.size(); ++i)
      ui.overlayText[i] = i < options.overlay.size() ? options.overlay[i].text : "";
  }
}

std::array<bool*, kSectionNames.size()> sectionsShown(UiState& ui) {
  return {&ui.showSimulation, &ui.showRewind, &ui.showWorld, &ui.showDraw, &ui.showStats, &ui.showLab};
}

void resetLayout(UiState& ui) {
  for (bool* shown : sectionsShown(ui)) *shown = true;
  ui.panelsHidden = false;
  ui.unfolded = kDefaultUnfolded;
  ui.resetLayout = true;
}

void remember(const UiState& ui, UserSettings& user) {
  user.showSimulation = ui.showSimulation;
  user.showWorld = ui.showWorld;
  user.showDraw = ui.showDraw;
  user.showStats = ui.showStats;
  user.drawMode = std::string(toString(ui.draw.mode));
  user.markers = ui.draw.markers;
  user.showRewind = ui.showRewind;
  user.showLab = ui.showLab;
  user.colorBy = std::string(toString(ui.draw.coloring));
  user.throwSpeed = ui.throwSpeed;
  user.recordingBudgetMb = ui.recordingBudgetMb;
}

namespace {

void settingsSection(Session& session, UiState& ui) {
  const scenes::Scene& scene = session.scene();
  const phys::World& world = session.scene().world;
  ImGui::TextWrapped("%s: %s", scene.name.c_str(), scene.description.c_str());
  ImGui::Text("t = %.2f s, step %ld", world.time(), world.stepCount());
  // The box shows the state and a click does what Space does (togglePause): during Play, which
  // shows the recording paused, a click stops Play rather than leave it going with the clock running.
  bool paused = ui.paused;
  if (ImGui::Checkbox("Pause (Space)", &paused)) togglePause(ui);
  ImGui::SameLine();
  if (ImGui::Button("Step (N)")) stepOnce(session, ui);
  ImGui::SameLine();
  if (ImGui::Button("Reset (F5)")) ui.reloadRequested = true;
  // Clamped when typed too (Ctrl+click): 0 would stop the clock unsaid, and a negative scale run up
  // a debt of simulated time that kept the world still for as long again once set right.
  ImGui::SliderFloat("time scale", &ui.timeScale, 0.05f, 4.0f, "%.2f",
                     ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);

  // The settings edited through a copy and handed back to the setter, which validates; the
  // ranges below keep every value valid.
  phys::SolverSettings s = world.solverSettings();
  bool changed = false;
  int method = static_cast<int>(s.method);
  if (ImGui::Combo("method", &method, "gauss-seidel\0jacobi\0xpbd\0shake\0")) {
    s.method = static_cast<phys::SolverMethod>(method);
    changed = true;
  }
  double dtMs = s.dt * 1000.0;
  if (sliderReal("dt (ms)", dtMs, 1.0f, 66.7f, "%.2f", ImGuiSliderFlags_Logarithmic)) {
    s.dt = dtMs / 1000.0;
    changed = true;
  }
  changed |= settingSlider("substeps", s.substeps, 1, 64, ui);
  changed |= settingSlider("iterations", s.iterations, 1, 64, ui);
  changed |= sliderReal("feature epsilon (m)", s.featureEpsilon, 0.0f, 0.1f, "%.4f");
  changed |= sliderReal("restitution", s.restitution, 0.0f, 1.0f, "%.2f");
  changed |=
      sliderReal("compliance (m/N, xpbd)", s.compliance, 0.0f, 1e-2f, "%.1e", ImGuiSliderFlags_Logarithmic);
  changed |= sliderReal("body damping", s.bodyDamping, 0.0f, 1.0f, "%.2f");
  changed |= sliderReal("depenetration (m/s)", s.maxDepenetrationSpeed, 0.1f, 100.0f, "%.2f",
                        ImGuiSliderFlags_Logarithmic);
  // Up to the machine's threads (or the scene's number, if larger); the result is the same for any.
  const int mostThreads =
      std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, phys::kMaxThreads);
  changed |= settingSlider("threads", s.threads, 1, std::max(mostThreads, s.threads), ui);
  changed |= ImGui::Checkbox("joint projection", &s.jointProjection.enabled);
  ImGui::SameLine();
  greyWrapped("rigid joints closed exactly after each substep");
  changed |= ImGui::Checkbox("keep spin", &s.keepSpin);
  ImGui::SameLine();
  greyWrapped("its own sticks keep a body's spin");
  changed |= ImGui::Checkbox("sleep", &s.sleep.enabled);
  ImGui::SameLine();
  greyWrapped("islands at rest " + figure("%.1f", s.sleep.time) + " s under " +
              figure("%.2f", s.sleep.speed) + " m/s");
  if (changed) {
    const std::string error = session.setSolverSettings(s);
    ui.message = error.empty() ? "solver: " + describeSolver(s) + " (applied without restart)" : error;
  }

  // Friction lives in the materials; the panel's is the ground's, which every contact with the
  // ground combines with the body's own (geometric mean).
  phys::WorldSettings w = world.worldSettings();
  double mu = w.groundMaterial.staticFriction;
  if (mu > 0.0) ui.groundFrictionRatio = w.groundMaterial.dynamicFriction / mu;
  if (sliderReal("ground friction", mu, 0.0f, 2.0f, "%.2f")) {
    w.groundMaterial.staticFriction = mu;
    w.groundMaterial.dynamicFriction = mu * ui.groundFrictionRatio;
    const std::string error = session.setWorldSettings(w);  // "" left the last command's words
    ui.message = error.empty() ? "world settings applied without restart" : error;
  }
}

// The recording's timeline: drag it to show any recorded step (the world pauses there); stepping
// or any command from a step shown resumes the run from it, and the recording forks.
void rewindSection(Session& session, UiState& ui) {
  const Recording& r = session.recording();
  if (session.overlayActive()) {
    greyWrapped(
        "paused while the method overlay runs: run 0's steps are recorded, to rewind once the overlay "
        "stops (the other runs are not)");
    return;
  }
  if (r.empty()) {
    greyWrapped("nothing recorded yet");
    if (ImGui::Button("Open...")) ui.openRecordingRequested = true;
    return;
  }
  const long now = session.scene().world.stepCount();
  auto go = [&](long step) {
    ui.paused = true;
    ui.replaying = false;
    const std::string error = session.rewindTo(step);
    ui.message = error.empty() ? session.status() : error;
  };
  int step = static_cast<int>(now);
  if (ImGui::SliderInt("step", &step, static_cast<int>(r.first()), static_cast<int>(r.last()), "%d",
                       ImGuiSliderFlags_AlwaysClamp) &&
      step != now) {
    go(step);
  }
  if (ImGui::Button("|<")) go(r.first());
  ImGui::SameLine();
  if (ImGui::Button("< (B)") && now > r.first()) go(now - 1);
  ImGui::SameLine();
  if (ImGui::Button("> (N)")) {
    if (now < r.last())
      go(now + 1);  // along the recording: the same step, shown without forking it
    else
      ui.stepOnce = true;
  }
  ImGui::SameLine();
  if (ImGui::Button(">|") && now != r.last()) go(r.last());
  ImGui::SameLine();
  // Play shows the recording as it was, at the clock's pace, without forking it; it stops at
  // the end, or when Space or a command resumes the run.
  if (ImGui::Button(ui.replaying ? "Stop" : "Play")) {
    if (!ui.replaying && now >= r.last()) go(r.first());
    ui.replaying = !ui.replaying;
    ui.paused = true;
  }
  greyWrapped(figure("%.1f", r.seconds()) + " s recorded (steps " + std::to_string(r.first()) + " to " +
              std::to_string(r.last()) + "), " + figure("%.1f", static_cast<double>(r.bytes()) / (1 << 20)) +
              " MB kept");
  if (ImGui::SliderInt("budget (MB)", &ui.recordingBudgetMb, kMinRecordingBudgetMb, kMaxRecordingBudgetMb,
                       "%d", ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp)) {
    session.setRecordingBudget(static_cast<std::size_t>(ui.recordingBudgetMb) << 20);
  }
  if (const std::optional<double> saving = session.savingProgress()) {
    ImGui::ProgressBar(static_cast<float>(*saving), ImVec2(ImGui::GetFontSize() * 8.0f, 0.0f), "saving");
  } else if (ImGui::Button("Save...")) {
    ui.saveRecordingRequested = true;
  }
  ImGui::SameLine();
  if (ImGui::Button("Open...")) ui.openRecordingRequested = true;
}

// Each method's colour on the Lab chart.
ImU32 methodColor(phys::SolverMethod m) {
  switch (m) {
    case phys::SolverMethod::GaussSeidel:
      return IM_COL32(230, 130, 40, 255);
    case phys::SolverMethod::Jacobi:
      return IM_COL32(80, 140, 230, 255);
    case phys::SolverMethod::Xpbd:
      return IM_COL32(90, 190, 90, 255);
    case phys::SolverMethod::Shake:
      return IM_COL32(210, 90, 200, 255);
  }
  return IM_COL32_WHITE;
}

// Error against cost on log axes, as docs/results.md's charts: each setting a dot in its method's
// colour (a cross at the top when it blew up), the Pareto front as a line, the world's own setting
// ringed. Hovering names a point; clicking it applies its method, iterations and substeps.
void labChart(Session& session, UiState& ui, const std::vector<LabPoint>& points) {
  const float width = ImGui::GetContentRegionAvail().x, height = 200.0f;
  const ImVec2 at = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("##chart", ImVec2(width, height));
  const bool clicked = ImGui::IsItemClicked(ImGuiMouseButton_Left);
  const bool hovered = ImGui::IsItemHovered();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 lo(at.x + 34.0f, at.y + 4.0f), hi(at.x + width - 4.0f, at.y + height - 16.0f);
  draw->AddRectFilled(lo, hi, IM_COL32(25, 27, 32, 255));
  double msLo = 1e300, msHi = 0.0, errLo = 1e300, errHi = 0.0;
  for (const LabPoint& p : points) {
    msLo = std::min(msLo, p.msPerStep);
    msHi = std::max(msHi, p.msPerStep);
    if (p.blewUp) continue;
    errLo = std::min(errLo, std::max(p.error, 1e-9));
    errHi = std::max(errHi, std::max(p.error, 1e-9));
  }
  if (points.empty() || !(msHi > 0.0)) return;
  if (errHi < errLo) errLo = errHi = 1.0;
  const double lx0 = std::log10(std::max(msLo, 1e-6)) - 0.1, lx1 = std::log10(std::max(msHi, 1e-6)) + 0.1;
  const double ly0 = std::log10(errLo) - 0.2, ly1 = std::log10(errHi) + 0.2;
  auto place = [&](double ms, double err) {
    const double fx = (std::log10(std::max(ms, 1e-6)) - lx0) / (lx1 - lx0);
    const double fy = (std::log10(std::max(err, 1e-9)) - ly0) / (ly1 - ly0);
    return ImVec2(lo.x + static_cast<float>(fx) * (hi.x - lo.x),
                  hi.y - static_cast<float>(fy) * (hi.y - lo.y));
  };
  const ImU32 label = IM_COL32(170, 170, 170, 255);
  draw->AddText(ImVec2(at.x, lo.y), label, figure("%.0e", std::pow(10.0, ly1)).c_str());
  draw->AddText(ImVec2(at.x, hi.y - 12.0f), label, figure("%.0e", std::pow(10.0, ly0)).c_str());
  draw->AddText(ImVec2(lo.x, hi.y + 2.0f), label, (figure("%.2g", std::pow(10.0, lx0)) + " ms").c_str());
  const std::string right = figure("%.2g", std::pow(10.0, lx1)) + " ms/step";
  draw->AddText(ImVec2(hi.x - ImGui::CalcTextSize(right.c_str()).x, hi.y + 2.0f), label, right.c_str());
  const std::vector<LabPoint> front = paretoFront(points);
  for (std::size_t k = 1; k < front.size(); ++k) {
    draw->AddLine(place(front[k - 1].msPerStep, front[k - 1].error),
                  place(front[k].msPerStep, front[k].error), IM_COL32(235, 235, 235, 200), 1.5f);
  }
  const phys::SolverSettings& now = session.scene().world.solverSettings();
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  const LabPoint* nearest = nullptr;
  float nearestDistance = 8.0f;
  for (const LabPoint& p : points) {
    ImVec2 c = place(p.msPerStep, p.blewUp ? std::pow(10.0, ly1) : p.error);
    if (p.blewUp) {
      c.y = lo.y + 4.0f;
      draw->AddLine(ImVec2(c.x - 3, c.y - 3), ImVec2(c.x + 3, c.y + 3), methodColor(p.method));
      draw->AddLine(ImVec2(c.x - 3, c.y + 3), ImVec2(c.x + 3, c.y - 3), methodColor(p.method));
    } else {
      draw->AddCircleFilled(c, 3.0f, methodColor(p.method));
    }
    if (p.method == now.method && p.iterations == now.iterations && p.substeps == now.substeps)
      draw->AddCircle(c, 7.0f, IM_COL32_WHITE, 0, 2.0f);
    const float d = std::hypot(c.x - mouse.x, c.y - mouse.y);
    if (hovered && d < nearestDistance) {
      nearest = &p;
      nearestDistance = d;
    }
  }
  if (nearest == nullptr) return;
  const std::string name = lab::settingLabel(nearest->method, nearest->iterations, nearest->substeps);
  const std::string error =
      nearest->blewUp ? "none (it blew up)" : figure("%.3g", nearest->error * 1000.0) + " mm";
  ImGui::SetTooltip("%s: %s ms a step, error %s\nclick to use it", name.c_str(),
                    figure("%.3g", nearest->msPerStep).c_str(), error.c_str());
  if (clicked) {
    phys::SolverSettings s = now;
    s.method = nearest->method;
    s.iterations = nearest->iterations;
    s.substeps = nearest->substeps;
    const std::string refused = session.setSolverSettings(s);
    ui.message = refused.empty() ? "solver: " + describeSolver(s) + " (from the Lab chart)" : refused;
  }
}

void labSection(Session& session, UiState& ui) {
  greyWrapped(
      "The scene's file under 4 methods x 1, 2, 4 iterations x 1, 2, 4, 8 substeps, each run 1 s "
      "against the scene's exact answers or a converged reference, as `lab sweep` measures it.");
  if (ui.lab.running()) {
    if (ui.lab.cancelling())
      ImGui::TextDisabled("cancelling...");
    else if (ImGui::Button("Cancel"))
      ui.lab.cancel();
    ImGui::SameLine();
    const int total = std::max(ui.lab.total(), 1);
    ImGui::ProgressBar(static_cast<float>(ui.lab.done()) / static_cast<float>(total), ImVec2(-1.0f, 0.0f),
                       (std::to_string(ui.lab.done()) + " of " + std::to_string(ui.lab.total())).c_str());
  } else if (ImGui::Button(ui.lab.points().empty() ? "Sweep this scene" : "Sweep again")) {
    ui.lab.start(session.file());
  }
  if (const std::string error = ui.lab.error(); !error.empty()) greyWrapped("stopped: " + error);
  const std::vector<LabPoint> points = ui.lab.points();
  if (points.empty()) return;
  if (ui.lab.file() != session.file())
    greyWrapped("of " + ui.lab.file().filename().string() + ", not this scene");
  labChart(session, ui, points);
  for (phys::SolverMethod m : {phys::SolverMethod::GaussSeidel, phys::SolverMethod::Jacobi,
                               phys::SolverMethod::Xpbd, phys::SolverMethod::Shake}) {
    const ImU32 c = methodColor(m);
    ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(c), "%s", std::string(phys::toString(m)).c_str());
    ImGui::SameLine();
  }
  ImGui::NewLine();
}

// The joints' drives (phys::JointDrive: rigid joints' and particle joints'): one strength for all,
// from limp to holding the pose each joint's target gives; each joint keeps its own stiffness, shown
// as the range the scene has.
void drivesBlock(Session& session, UiState& ui) {
  const phys::World& world = session.scene().world;
  const std::size_t rigid = world.rigidJoints().size(), joints = rigid + world.particleJoints().size();
  if (joints == 0) return;
  auto driveOf = [&](std::size_t k) -> const phys::JointDrive& {
    return k < rigid ? world.jointDrive(k) : world.particleJointDrive(k - rigid);
  };
  double strength = 0.0, weakest = 1.0, least = driveOf(0).stiffness, most = least;
  for (std::size_t k = 0; k < joints; ++k) {
    const phys::JointDrive& d = driveOf(k);
    strength = std::max(strength, d.strength);
    weakest = std::min(weakest, d.strength);
    least = std::min(least, d.stiffness);
    most = std::max(most, d.stiffness);
  }
  auto range = [](double lo, double hi, const char* format) {
    return lo == hi ? figure(format, lo) : figure(format, lo) + " to " + figure(format, hi);
  };
  if (sliderReal("drive strength", strength, 0.0f, 1.0f, "%.2f")) {
    const std::string error = session.setDriveStrength(strength);
    ui.message = error.empty() ? "drive strength " + figure("%.2f", strength) + " on every joint" : error;
  }
  greyWrapped(std::to_string(joints) + " driven joints at strength " + range(weakest, strength, "%.2f") +
              " (0 limp, 1 holds the pose; the slider sets all), stiffness at 1/2 " +
              range(least, most, "%.0f") + " N m/rad");
}

const char* stateName(phys::CharacterState state) {
  switch (state) {
    case phys::CharacterState::Active:
      return "active";
    case phys::CharacterState::Falling:
      return "falling (going limp)";
    case phys::CharacterState::Down:
      return "down";
    case phys::CharacterState::GettingUp:
      return "getting up";
    case phys::CharacterState::LettingGo:
      return "on its feet, let go";
  }
  return "";
}

// The clip files beside `folder`'s clip that clips::loadClip may read, by name; read only while
// the list is open, so a closed list costs nothing a frame.
std::vector<std::filesystem::path> clipFiles(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> files;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
    if (entry.is_regular_file(error) &&
        (ext == ".bvh" || ext == ".fbx" || ext == ".gltf" || ext == ".glb" || ext == ".x" || ext == ".dae"))
      files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Character k's clip: chosen among the files beside it, scrubbed in time, looping or not.
std::string clipControls(Session& session, std::size_t k) {
  const phys::Character& c = session.scene().world.characters()[k];
  const std::filesystem::path playing(c.now.clip->name);
  std::string error;
  if (ImGui::BeginCombo("clip", playing.filename().string().c_str())) {
    for (const std::filesystem::path& file : clipFiles(playing.parent_path())) {
      if (ImGui::Selectable(file.filename().string().c_str(), file.filename() == playing.filename()))
        error = session.playCharacterClip(k, file, c.now.loop);
    }
    ImGui::EndCombo();
  }
  const double duration = c.now.clip->duration();
  double time = c.now.loop && duration > 0.0 ? std::fmod(c.now.time, duration) : c.now.time;
  phys::Playback playback = c.now;
  if (sliderReal("clip time (s)", time, 0.0f, static_cast<float>(duration), "%.2f")) {
    playback.time = time;
    error = session.setCharacterPlayback(k, playback, 0.0);
  }
  bool loop = c.now.loop;
  if (ImGui::Checkbox("loop", &loop)) {
    playback.loop = loop;
    error = session.setCharacterPlayback(k, playback, 0.0);
  }
  return error;
}

// The scene's characters (phys::Character): each one's clip and state, its clip's controls, its strengths,
// reaction threshold and turn-in time, and shoves to watch it stagger (200 N) or fall (2000 N).
void animationBlock(Session& session, UiState& ui) {
  const std::size_t count = session.scene().world.characters().size();
  if (count == 0) return;
  ImGui::Separator();
  ImGui::TextUnformatted("Animation");
  ImGui::SameLine();
  ImGui::Checkbox("show target poses", &ui.draw.targets);
  for (std::size_t k = 0; k < count; ++k) {
    const phys::Character& c = session.scene().world.characters()[k];
    ImGui::PushID(static_cast<int>(k));
    if (ImGui::TreeNode("character", "%s: %s", c.ragdoll.c_str(), stateName(c.state))) {
      const std::string clip = std::filesystem::path(c.now.clip->name).filename().string();
      greyWrapped(clip + " at " + figure("%.2f", c.now.time) + " s" +
                  (c.queued
                       ? ", then " + std::filesystem::path(c.queued->playback.clip->name).filename().string()
                       : std::string()) +
                  "; last blow " + figure("%.2f", c.lastImpact) + " m/s");
      std::string error = clipControls(session, k);
      double strength = c.goalStrength, balance = c.goalBalance, threshold = c.reaction.threshold;
      if (sliderReal("strength", strength, 0.0f, 1.0f, "%.2f"))
        error = session.setCharacterStrength(k, strength);
      if (sliderReal("balance", balance, 0.0f, 1.0f, "%.2f")) error = session.setCharacterBalance(k, balance);
      if (sliderReal("react at (m/s)", threshold, 0.0f, 10.0f, "%.2f"))
        error = session.setReactionThreshold(k, threshold);
      // How long a turn from a far pose holds each pass to a share of the gap (phys::kTurnInShare).
      double turnIn = c.turnInTime;
      if (sliderReal("turn-in (s)", turnIn, 0.0f, 1.0f, "%.2f"))
        error = session.setCharacterTurnIn(k, turnIn);
      // Each joint's share of the strength: an arm let hang, a stiff neck.
      if (ImGui::TreeNode("parts", "parts' share of the strength")) {
        for (std::size_t b = 1; b < c.bones.size(); ++b) {
          const std::string& bone = c.now.clip->bones[static_cast<std::size_t>(c.bones[b].clipBone)];
          double share = c.partStrength[b];
          if (sliderReal(bone.c_str(), share, 0.0f, 1.0f, "%.2f"))
            error = session.setPartStrength(k, bone, share);
        }
        ImGui::TreePop();
      }
      if (ImGui::Button("push 200 N")) error = session.pushCharacter(k, kPushForce);
      ImGui::SameLine();
      if (ImGui::Button("shove 2000 N")) error = session.pushCharacter(k, kKnockForce);
      if (!error.empty()) ui.message = error;
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
}

void worldSection(Session& session, UiState& ui) {
  phys::WorldSettings w = session.scene().world.worldSettings();
  int mode = static_cast<int>(w.gravityMode);
  if (ImGui::Combo("gravity (G)", &mode, "uniform\0point\0")) {
    if (mode != static_cast<int>(w.gravityMode)) {
      session.toggleGravityMode();
      ui.message = session.status();  // as G says it
    }
    w = session.scene().world.worldSettings();
  }
  bool changed = false;
  if (w.gravityMode == phys::GravityMode::Uniform) {
    double g = glm::length(w.gravity);
    if (sliderReal("strength (m/s^2, Y/H)", g, 0.0f, static_cast<float>(kMaxRaisedGravity), "%.2f")) {
      const double old = glm::length(w.gravity);
      w.gravity = (old > 0.0 ? w.gravity / old : phys::Vec3(0, -1, 0)) * g;
      changed = true;
    }
  } else {
    changed |= sliderReal("strength (m/s^2, Y/H)", w.gravityStrength, 0.0f,
                          static_cast<float>(kMaxRaisedGravity), "%.2f");
    float p[3] = {static_cast<float>(w.gravityPoint.x), static_cast<float>(w.gravityPoint.y),
                  static_cast<float>(w.gravityPoint.z)};
    // Typed values (Ctrl+click) can be anything; the world refuses a non-finite point.
    if (ImGui::DragFloat3("point (m)", p, 0.05f, -1e4f, 1e4f, "%.2f", ImGuiSliderFlags_AlwaysClamp)) {
      w.gravityPoint = phys::Vec3(p[0], p[1], p[2]);
      changed = true;
    }
  }
  changed |= sliderReal("damping (1/s, U/J)", w.damping, 0.0f, 5.0f, "%.2f");
  if (changed) {
    const std::string error = session.setWorldSettings(w);
    ui.message = error.empty() ? "world settings applied without restart" : error;
  }
  ImGui::Text("ground: %s", w.ground ? "yes" : "none");
  drivesBlock(session, ui);
  animationBlock(session, ui);
  // What F, R and T throw: boxes of this model, ragdolls of its kind.
  ImGui::SliderFloat("throw speed (m/s)", &ui.throwSpeed, 0.0f, kMaxThrowSpeed, "%.1f",
                     ImGuiSliderFlags_AlwaysClamp);
  int thrown = static_cast<int>(session.throwModel());
  if (ImGui::Combo("thrown bodies", &thrown, "corners\0tetra\0rigid\0"))
    session.setThrowModel(static_cast<phys::BodyModel>(thrown));
}

void drawSection(UiState& ui) {
  int mode = static_cast<int>(ui.draw.mode);
  ImGui::RadioButton("filled", &mode, 0);
  ImGui::SameLine();
  ImGui::RadioButton("wireframe", &mode, 1);
  ImGui::SameLine();
  ImGui::RadioButton("constraints (Tab)", &mode, 2);
  ui.draw.mode = static_cast<DrawMode>(mode);
  ImGui::Checkbox("markers (C)", &ui.draw.markers);
  ImGui::SameLine();
  ImGui::Checkbox("AABBs", &ui.draw.bounds);
  ImGui::SameLine();
  ImGui::Checkbox("contact normals", &ui.draw.contacts);
  ImGui::Checkbox("particles", &ui.draw.particles);
  ImGui::SameLine();
  ImGui::Checkbox("sticks over meshes", &ui.draw.sticks);
  ImGui::SameLine();
  ImGui::Checkbox("trails", &ui.draw.trails);
  ImGui::SameLine();
  ImGui::Checkbox("exact answers", &ui.draw.exact);
  ImGui::SameLine();
  ImGui::Checkbox("target poses", &ui.draw.targets);
  // The answer is the file's: beside a world it no longer fits it would be wrong, so it is hidden.
  if (ui.draw.exact && !ui.exactHidden.empty()) greyWrapped("exact answer hidden: " + ui.exactHidden);
  ImGui::Checkbox("shadows", &ui.draw.shadows);
  int coloring = static_cast<int>(ui.draw.coloring);
  ImGui::Text("colour by");
  ImGui::SameLine();
  ImGui::RadioButton("kind", &coloring, 0);
  ImGui::SameLine();
  ImGui::RadioButton("body", &coloring, 1);
  ImGui::SameLine();
  ImGui::RadioButton("island", &coloring, 2);
  ImGui::SameLine();
  ImGui::RadioButton("sleep", &coloring, 3);
  ui.draw.coloring = static_cast<BodyColoring>(coloring);
}

void statsSection(const Session& session, UiState& ui) {
  const phys::World& world = session.scene().world;
  const phys::Profile& p = world.profile();
  ImGui::Text("frame %.2f ms, last step %.3f ms", ui.frameMs, p.total);
  // Simulated seconds per wall second: red when the physics cannot keep up with the time scale.
  if (const std::optional<double> factor = ui.realTime.factor()) {
    if (ui.realTime.fallingBehind(ui.timeScale))
      ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.45f, 1.0f), "real time x%.2f: the physics cannot keep up",
                         *factor);
    else
      ImGui::Text("real time x%.2f", *factor);
  } else {
    greyWrapped("real time: not timed (paused or screenshot)");
  }
  // The step's stages two to a line, in the step's order (ms, summed over the substeps).
  for (std::size_t i = 0; i < phys::kStageCount; i += 2) {
    const auto a = static_cast<phys::Stage>(i);
    const std::string_view na = phys::toString(a);
    if (i + 1 == phys::kStageCount) {
      ImGui::Text("%-12.*s %7.3f", static_cast<int>(na.size()), na.data(), p[a]);
      break;
    }
    const auto b = static_cast<phys::Stage>(i + 1);
    const std::string_view nb = phys::toString(b);
    ImGui::Text("%-12.*s %7.3f  %-12.*s %7.3f", static_cast<int>(na.size()), na.data(), p[a],
                static_cast<int>(nb.size()), nb.data(), p[b]);
  }
  ImGui::Separator();
  for (const StatsLine& line : statsLines(world)) {
    // Wrapped: a narrow column must not cut a line off.
    if (line.warning) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.45f, 1.0f));
    ImGui::TextWrapped("%s", line.text.c_str());
    if (line.warning) ImGui::PopStyleColor();
  }
  ImGui::Separator();
  const ImVec2 plotSize(ImGui::GetContentRegionAvail().x, 40.0f);  // three fit under the stages
  char overlay[64];
  std::snprintf(overlay, sizeof overlay, "step %.3f ms (max %.3f)", ui.stepMs.last(), ui.stepMs.max());
  ImGui::PlotLines("##step", ui.stepMs.data(), ui.stepMs.size(), ui.stepMs.offset(), overlay, 0.0f,
                   std::max(ui.stepMs.max() * 1.1f, 1e-3f), plotSize);
  std::snprintf(overlay, sizeof overlay, "max stick error %s", figure("%.2e", ui.maxError.last()).c_str());
  ImGui::PlotLines("##maxerr", ui.maxError.data(), ui.maxError.size(), ui.maxError.offset(), overlay, 0.0f,
                   std::max(ui.maxError.max() * 1.1f, 1e-6f), plotSize);
  std::snprintf(overlay, sizeof overlay, "rms stick error %s", figure("%.2e", ui.rmsError.last()).c_str());
  ImGui::PlotLines("##rmserr", ui.rmsError.data(), ui.rmsError.size(), ui.rmsError.offset(), overlay, 0.0f,
                   std::max(ui.rmsError.max() * 1.1f, 1e-6f), plotSize);
  ImGui::TextDisabled("plots: the last 10 s of wall time");
}

}  // namespace

ScreenRect panelColumn(float windowWidth, float windowHeight, float top, float bottom) {
  const float width =
      std::min(std::clamp(windowWidth * kColumnShare, kColumnMin, kColumnMax), windowWidth * 0.5f);
  return {windowWidth - width, top, width, std::max(windowHeight - top - bottom, 0.0f)};
}

ScreenRect sceneView(float windowWidth, float windowHeight, bool panelsShown) {
  if (!panelsShown) return {0.0f, 0.0f, windowWidth, windowHeight};
  return {0.0f, 0.0f, panelColumn(windowWidth, windowHeight, 0.0f, 0.0f).x, windowHeight};
}

void drawPanels(Session& session, UiState& ui) {
  const bool reset = ui.resetLayout;
  ui.resetLayout = false;
  if (ui.panelsHidden) return;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const ScreenRect c = panelColumn(display.x, display.y, ImGui::GetFrameHeight(), statusLineHeight());
  ImGui::SetNextWindowPos(ImVec2(c.x, c.y), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(c.width, c.height), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.94f);
  ImGui::Begin("Panels", nullptr,
               ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                   ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoBringToFrontOnFocus);
  // Sliders take what the labels leave: the longest label is "compliance (m/N, xpbd)".
  ImGui::PushItemWidth(-ImGui::GetFontSize() * 12.5f);  // 162 pixels for the labels
  if (beginSection(kSectionTitles[0], &ui.showSimulation, ui.unfolded[0], reset)) {
    settingsSection(session, ui);
    // Last: starting the overlay replaces the scene the section above drew from.
    overlaySection(session, ui);
  }
  if (beginSection(kSectionTitles[1], &ui.showRewind, ui.unfolded[1], reset)) rewindSection(session, ui);
  if (beginSection(kSectionTitles[2], &ui.showWorld, ui.unfolded[2], reset)) worldSection(session, ui);
  if (beginSection(kSectionTitles[3], &ui.showDraw, ui.unfolded[3], reset)) drawSection(ui);
  if (beginSection(kSectionTitles[4], &ui.showStats, ui.unfolded[4], reset)) statsSection(session, ui);
  if (beginSection(kSectionTitles[5], &ui.showLab, ui.unfolded[5], reset)) labSection(session, ui);
  ImGui::PopItemWidth();
  ImGui::End();
}

void drawLegend(const Session& session, const UiState& ui) {
  if (!session.overlayActive()) return;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const ScreenRect view = sceneView(display.x, display.y, !ui.panelsHidden);
  // At the foot of the scene, above the status line.
  ImGui::SetNextWindowPos(ImVec2(view.x + view.width * 0.5f, display.y - statusLineHeight() - 4.0f),
                          ImGuiCond_Always, ImVec2(0.5f, 1.0f));
  ImGui::SetNextWindowBgAlpha(0.85f);
  // Within the scene's part of the window: a long setting wraps rather than covering the panels.
  const float width = std::max(view.width - 16.0f, 200.0f);
  ImGui::SetNextWindowSizeConstraints(ImVec2(0.0f, 0.0f), ImVec2(width, display.y * 0.5f));
  ImGui::Begin("Overlay", nullptr,
               ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings);
  const double now = session.runs().front().scene->world.time();
  int id = 0;
  for (const Run& run : session.runs()) {
    const phys::SolverSettings& s = run.scene->world.solverSettings();
    ImGui::PushID(id++);
    ImGui::ColorButton("##c", ImVec4(run.color.r, run.color.g, run.color.b, 1.0f), 0, ImVec2(14, 14));
    ImGui::SameLine();
    ImGui::PushTextWrapPos(width - 16.0f);
    ImGui::TextWrapped("%s   %s   %.3f ms/step (median), error %s", run.label.c_str(),
                       describeSolver(s).c_str(), run.medianMs(),
                       figure("%.1e", run.scene->world.metrics().maxConstraintError).c_str());
    ImGui::PopTextWrapPos();
    // The runs are drawn at one moment only while each keeps up with run 0's clock.
    if (const double behind = run.behind(now); behind > 0.0) {
      ImGui::TextColored(ImVec4(1.0f, 0.6f, 0.2f, 1.0f), "%s s behind (%d steps a frame at most)",
                         figure("%.3f", behind).c_str(), kMaxCatchUpSteps);
    }
    ImGui::PopID();
  }
  ImGui::End();
}

void drawHelp(UiState& ui) {
  if (!ui.showHelp) return;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.5f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowBgAlpha(0.95f);
  ImGui::Begin("Controls (F1)", &ui.showHelp,
               ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings);
  if (ImGui::BeginTable("controls", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
    for (const Control& c : controls()) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(c.keys.data(), c.keys.data() + c.keys.size());
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(c.action.data(), c.action.data() + c.action.size());
    }
    ImGui::EndTable();
  }
  ImGui::End();
}

float statusLineHeight() {
  return ImGui::GetTextLineHeightWithSpacing() + 6.0f;
}

void drawStatusAndCrosshair(const Session& session, const UiState& ui) {
  // Under every window, so that dialogs and panels cover them.
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const ScreenRect view = sceneView(display.x, display.y, !ui.panelsHidden);
  const ImVec2 c(view.x + view.width * 0.5f, view.y + view.height * 0.5f);
  const ImU32 white = IM_COL32(255, 255, 255, 200);
  draw->AddLine(ImVec2(c.x - 8, c.y), ImVec2(c.x + 8, c.y), white);
  draw->AddLine(ImVec2(c.x, c.y - 8), ImVec2(c.x, c.y + 8), white);
  const std::string& text = ui.message.empty() ? session.status() : ui.message;
  // Whole: a fixed buffer cut long paths short, sometimes inside a UTF-8 character.
  const std::string line = std::string(ui.replaying ? "PLAYING THE RECORDING   |   "
                                       : ui.paused  ? "PAUSED   |   "
                                                    : "") +
                           std::string(toString(ui.draw.mode)) + "   |   " + text +
                           "   |   F1: controls, F2: panels";
  const ImVec2 at(8.0f, display.y - statusLineHeight() + 2.0f);
  draw->AddRectFilled(ImVec2(0, at.y - 2), ImVec2(display.x, display.y), IM_COL32(20, 20, 24, 230));
  draw->AddText(at, IM_COL32(235, 235, 235, 255), line.c_str(), line.c_str() + line.size());
}

}  // namespace sandbox
