#pragma once
// The Stats panel's figures as text, apart from ImGui so that tests and the soak can read what
// the user is shown. A figure that is not finite (the energies of a world under a gravity of
// 1e308 m/s^2 overflow: docs/physics.md, "Metrics") reads "overflow", never "nan" or "inf".
#include <string>
#include <vector>

#include "physics/world.h"

namespace sandbox {

/// `value` printed with `format` (one printf conversion for a double), or "overflow".
std::string figure(const char* format, double value);

struct StatsLine {
  std::string text;
  bool warning = false;  ///< drawn in red: the guard has frozen something
};

/// The world's counts and metrics, one line each, as the Stats panel shows them.
std::vector<StatsLine> statsLines(const phys::World& world);

}  // namespace sandbox
