#include "panel.h"

#include <imgui.h>

#include "scenes/scene.h"

namespace sandbox {

void drawPanel(scenes::Scene& scene, PanelState& state) {
  phys::World& world = scene.world;
  ImGui::SetNextWindowPos(ImVec2(kPanelPosition.x, kPanelPosition.y), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(kPanelSize.x, kPanelSize.y), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(1.0f);  // opaque, so the scene behind never hides the text
  ImGui::Begin("Simulation", nullptr, ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove |
                                          ImGuiWindowFlags_NoCollapse);
  ImGui::TextWrapped("%s: %s", scene.name.c_str(), scene.description.c_str());
  ImGui::Text("t = %.2f s, step %ld", world.time(), world.stepCount());

  ImGui::Checkbox("Pause", &state.paused);
  ImGui::SameLine();
  if (ImGui::Button("Step")) state.stepOnce = true;
  ImGui::SameLine();
  if (ImGui::Button("Reset")) state.resetRequested = true;

  // The sliders edit copies and hand them back through the setters, which validate; the
  // ranges below keep every value valid, so the setters never refuse one.
  phys::SolverSettings solver = world.solverSettings();
  int method = static_cast<int>(solver.method);
  bool solverChanged = ImGui::Combo("method", &method, "gauss-seidel\0jacobi\0xpbd\0shake\0");
  solver.method = static_cast<phys::SolverMethod>(method);
  solverChanged |= ImGui::SliderInt("iterations", &solver.iterations, 1, 32);
  solverChanged |= ImGui::SliderInt("substeps", &solver.substeps, 1, 32);
  if (solverChanged) world.setSolverSettings(solver);

  // Each slider writes back only its own field, so touching one never rounds the other
  // through float (9.81 would become 9.8100004 and the run would no longer match the lab's).
  phys::WorldSettings settings = world.worldSettings();
  float damping = static_cast<float>(settings.damping);
  float gravity = static_cast<float>(-settings.gravity.y);
  if (ImGui::SliderFloat("damping (1/s)", &damping, 0.0f, 5.0f)) {
    settings.damping = damping;
    world.setWorldSettings(settings);
  }
  if (ImGui::SliderFloat("gravity (m/s^2)", &gravity, 0.0f, 30.0f)) {
    settings.gravity.y = -gravity;
    world.setWorldSettings(settings);
  }

  ImGui::Checkbox("sticks", &state.drawSticks);
  ImGui::SameLine();
  ImGui::Checkbox("contacts", &state.drawContacts);
  ImGui::SameLine();
  ImGui::Checkbox("bounds", &state.drawBounds);
  ImGui::SameLine();
  ImGui::Checkbox("particles", &state.drawParticles);

  ImGui::Separator();
  ImGui::Text("frame %.2f ms, physics %.3f ms", state.frameMs, state.stepMs);
  ImGui::Text("%zu particles, %zu sticks, %zu boxes", world.particles().size(),
              world.sticks().size(), world.boxes().size());
  const phys::Metrics m = world.metrics();
  ImGui::Text("energy %.3f J, max speed %.3f m/s", m.energy(), m.maxSpeed);
  ImGui::Text("stick error max %.2e rms %.2e", m.maxConstraintError, m.rmsConstraintError);
  ImGui::Text("contacts %d, frozen %d", m.contacts, m.frozen);
  if (!state.loadError.empty()) ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.4f, 1.0f), "%s", state.loadError.c_str());
  ImGui::TextDisabled("W/A/S/D/Q/E move, right mouse looks");
  ImGui::End();
}

}  // namespace sandbox
