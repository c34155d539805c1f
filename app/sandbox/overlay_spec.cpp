#include "overlay_spec.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>

namespace sandbox {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

std::optional<int> parseInt(std::string_view s) {
  int v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return v;
}

std::optional<double> parseDouble(std::string_view s) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

}  // namespace

phys::SolverSettings OverlaySpec::applyTo(phys::SolverSettings s) const {
  if (method) s.method = *method;
  if (iterations) s.iterations = *iterations;
  if (substeps) s.substeps = *substeps;
  if (dt) s.dt = *dt;
  if (bodyDamping) s.bodyDamping = *bodyDamping;
  if (restitution) s.restitution = *restitution;
  if (compliance) s.compliance = *compliance;
  if (epsilon) s.featureEpsilon = *epsilon;
  if (slop) s.contactSlop = *slop;
  if (depenetrationSpeed) s.maxDepenetrationSpeed = *depenetrationSpeed;
  return s;
}

ParsedOverlaySpec parseOverlaySpec(std::string_view text) {
  ParsedOverlaySpec out;
  OverlaySpec& spec = out.spec;
  spec.text = std::string(trim(text));
  if (spec.text.empty()) {
    out.error = "empty overlay settings; give key=value pairs such as iterations=8";
    return out;
  }
  std::string_view rest = spec.text;
  while (!rest.empty()) {
    const std::size_t comma = rest.find(',');
    const std::string_view item = trim(rest.substr(0, comma));
    rest = comma == std::string_view::npos ? std::string_view() : rest.substr(comma + 1);
    const std::size_t eq = item.find('=');
    if (eq == std::string_view::npos) {
      // Built in steps: GCC 12 warns falsely (-Wrestrict) about "'" + std::string(...).
      out.error.assign(1, '\'').append(item).append("' is not key=value");
      return out;
    }
    const std::string key(trim(item.substr(0, eq)));
    const std::string_view value = trim(item.substr(eq + 1));
    auto bad = [&](const char* want) { out.error = key + ": '" + std::string(value) + "' " + want; };
    auto real = [&](std::optional<double>& field) {
      field = parseDouble(value);
      if (!field) bad("is not a number");
    };
    if (key == "method") {
      spec.method = phys::parseSolverMethod(value);
      if (!spec.method) bad("must be gauss-seidel, jacobi, xpbd or shake");
    } else if (key == "iterations" || key == "substeps") {
      auto& field = key == "iterations" ? spec.iterations : spec.substeps;
      field = parseInt(value);
      if (!field) bad("is not a whole number");
    } else if (key == "dt") {
      real(spec.dt);
    } else if (key == "body-damping") {
      real(spec.bodyDamping);
    } else if (key == "restitution") {
      real(spec.restitution);
    } else if (key == "compliance") {
      real(spec.compliance);
    } else if (key == "epsilon") {
      real(spec.epsilon);
    } else if (key == "slop") {
      real(spec.slop);
    } else if (key == "depenetration-speed") {
      if (value == "none") {  // no limit, as <solver depenetration-speed="none">
        spec.depenetrationSpeed = std::numeric_limits<double>::infinity();
      } else {
        spec.depenetrationSpeed = parseDouble(value);
        if (!spec.depenetrationSpeed) bad("must be a number > 0 (m/s) or none");  // the loader's words
      }
    } else {
      out.error =
          "unknown key '" + key +
          "' (known: method, iterations, substeps, dt, body-damping, restitution, compliance, epsilon, slop, "
          "depenetration-speed)";
    }
    if (!out.error.empty()) return out;
  }
  // The ranges are the physics' own: ask it, so the message and the limits cannot drift apart.
  if (const std::string why = phys::validate(spec.applyTo({})); !why.empty()) {
    out.error = "'" + spec.text + "': " + why;
  }
  return out;
}

std::string describeSolver(const phys::SolverSettings& s) {
  char text[96];
  std::snprintf(text, sizeof text, "%s %dx%d dt %.3g ms", std::string(phys::toString(s.method)).c_str(),
                s.iterations, s.substeps, s.dt * 1000.0);
  return text;
}

}  // namespace sandbox
