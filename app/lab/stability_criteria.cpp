#include "stability_criteria.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

#include "bodies.h"
#include "expect_reader.h"
#include "numbers.h"
#include "text.h"

namespace lab::stability {
namespace {

// A run longer than this is a typo in a window (10 h of simulated time), not a test.
constexpr double kMaxWindowEnd = 36000.0;  // unit: s

std::string metricList() {
  std::string out;
  for (const MetricInfo& m : kMetrics) out += (out.empty() ? "" : ", ") + std::string(m.name);
  return out;
}

// A criterion's number is read as numbers.h reads it, except that the criteria have always taken
// a leading '+' as well, and a scene file that writes one must keep loading. One '+' before the
// digits, so "+-1" and "++1" stay errors.
std::string_view withoutPlus(std::string_view text) {
  if (text.size() > 1 && text.front() == '+' && text[1] != '+' && text[1] != '-') text.remove_prefix(1);
  return text;
}

std::optional<double> parseSignedNumber(std::string_view text) {
  return lab::parseNumber(withoutPlus(text));
}

// A flips bound: a whole count, printed whole ("2147483647", not %g's "2.14748e+09").
std::string countText(double flips) {
  return std::to_string(std::llround(flips));
}

double readPositive(ExpectReader& r, const std::string& name, const std::string& unit) {
  const std::string inUnit = unit.empty() ? "" : " (" + unit + ")";
  const std::string& raw = r.required(name, "a number > 0" + inUnit);
  const std::optional<double> v = parseSignedNumber(raw);
  if (!v || *v <= 0.0) r.fail(name, "'" + raw + "' must be a number > 0" + inUnit);
  return *v;
}

// over="T0 T1": the window in seconds, turned into whole steps of the scene's dt.
void readWindow(ExpectReader& r, Criterion& c, double dt) {
  const std::string& raw = r.required("over", "two times in s, \"from to\"");
  std::istringstream in(raw);
  std::string a, b, extra;
  in >> a >> b >> extra;
  const std::optional<double> from = parseSignedNumber(a), to = parseSignedNumber(b);
  if (!from || !to || !extra.empty()) r.fail("over", "'" + raw + "' must be two numbers, \"from to\" (s)");
  if (*from < 0.0 || *to <= *from || *to > kMaxWindowEnd) {
    r.fail("over", "'" + raw + "' must have 0 <= from < to <= " + formatNumber(kMaxWindowEnd) + " (s)");
  }
  c.from = *from;
  c.to = *to;
  if (std::llround(*to / dt) > kMaxSteps) {
    r.fail("over", "'" + raw + "' at the scene's dt " + formatNumber(dt) + " s is more than " +
                       std::to_string(kMaxSteps) + " steps");
  }
  c.fromStep = static_cast<int>(std::lround(*from / dt));
  c.toStep = static_cast<int>(std::lround(*to / dt));
  if (c.toStep <= c.fromStep) {
    r.fail("over", "'" + raw + "' is shorter than one step of the scene's dt " + formatNumber(dt) + " s");
  }
}

const scenes::NamedBody& findBody(ExpectReader& r, const scenes::Scene& scene, const std::string& name) {
  for (const scenes::NamedBody& b : scene.bodies) {
    if (b.name == name) return b;
  }
  r.fail("body", "no body named '" + name + "' in the scene");
}

void readBodies(ExpectReader& r, const scenes::Scene& scene, Criterion& c, bool allowAll) {
  c.body = r.required("body", allowAll ? "a body's name, or * for every body" : "a body's name");
  if (allowAll && c.body == "*") {
    const std::size_t count = scene.world.bodies().size() + looseParticles(scene.world).size();
    for (std::size_t i = 0; i < count; ++i) c.bodies.push_back(i);
    return;
  }
  const std::optional<std::size_t> slot = bodySlot(scene, c.body);
  if (!slot) r.fail("body", "no body named '" + c.body + "' in the scene");
  c.bodies.push_back(*slot);
}

void readStaysBehind(ExpectReader& r, const scenes::Scene& scene, Criterion& c) {
  readBodies(r, scene, c, false);
  const std::string& axis = r.required("axis", "x, y or z");
  if (axis != "x" && axis != "y" && axis != "z") r.fail("axis", "'" + axis + "' must be x, y or z");
  c.axis = axis[0] - 'x';
  const std::string* max = r.find("max");
  const std::string* min = r.find("min");
  if ((max == nullptr) == (min == nullptr))
    r.fail(max ? "min" : "max", "give exactly one of max and min (m): the plane");
  const std::string attribute = max ? "max" : "min";
  const std::optional<double> plane = parseSignedNumber(max ? *max : *min);
  if (!plane) r.fail(attribute, "'" + (max ? *max : *min) + "' must be a finite number (m)");
  c.limit = *plane;
  c.atLeast = min != nullptr;
  c.start = bodyPositions(scene.world)[c.bodies.front()][c.axis];
  // Strictly on its side: the figure is the share of the way from the start to the plane.
  if (c.atLeast ? c.start <= c.limit : c.start >= c.limit) {
    const std::string where = c.start == c.limit ? "on" : c.atLeast ? "already below" : "already above";
    r.fail(attribute, "the body starts at " + axis + " = " + formatNumber(c.start) + ", " + where +
                          " the plane " + formatLimit(c.limit) + " (it must start " +
                          (c.atLeast ? "above" : "below") + " it)");
  }
}

void readFlips(ExpectReader& r, const scenes::Scene& scene, Criterion& c) {
  c.body = r.required("body", "a box's name");
  const scenes::NamedBody& body = findBody(r, scene, c.body);
  if (body.kind != scenes::NamedBody::Kind::Body)
    r.fail("body", "'" + c.body + "' is a particle; flips needs a box");
  const phys::Vec3 h = scene.world.bodies()[body.index].halfExtents;
  if (h.x == h.y || h.y == h.z || h.x == h.z) {
    r.fail("body", "'" + c.body + "' needs three different side lengths to have a middle axis");
  }
  c.bodies.push_back(body.index);
  // A count at least min, at most max, or both: a dissipating solver flips too seldom (the body
  // settles about its major axis) or, nutating off the separatrix, too often.
  auto count = [&](const std::string& name) -> std::optional<int> {
    const std::string* raw = r.find(name);
    if (raw == nullptr) return std::nullopt;
    const std::optional<int> n = parseWholeNumber(withoutPlus(*raw), 1, std::numeric_limits<int>::max());
    if (!n) r.fail(name, "'" + *raw + "' must be a whole number >= 1");
    return n;
  };
  const std::optional<int> min = count("min"), max = count("max");
  if (!min && !max) r.fail("min", "is required, or max, or both (whole numbers of flips)");
  if (min && max && *max < *min) r.fail("max", "must be >= min");
  c.limit = min.value_or(0);
  c.upper = max ? static_cast<double>(*max) : kInf;
  c.atLeast = true;
}

Criterion parseOne(ExpectReader& r, const scenes::Scene& scene) {
  Criterion c;
  const std::string& metric = r.required("metric", metricList());
  const auto info = std::find_if(std::begin(kMetrics), std::end(kMetrics),
                                 [&](const MetricInfo& m) { return metric == m.name; });
  if (info == std::end(kMetrics)) r.fail("metric", "'" + metric + "' must be one of " + metricList());
  c.metric = info->metric;
  readWindow(r, c, scene.world.solverSettings().dt);
  if (c.metric == Metric::StaysBehind) {
    readStaysBehind(r, scene, c);
  } else if (c.metric == Metric::Flips) {
    readFlips(r, scene, c);
  } else {
    if (c.metric == Metric::Drift) readBodies(r, scene, c, true);
    c.limit = readPositive(r, "max", info->unit);
  }
  r.rejectUnknown(" for this metric");
  return c;
}

}  // namespace

const MetricInfo& metricInfo(Metric metric) {
  return *std::find_if(std::begin(kMetrics), std::end(kMetrics),
                       [&](const MetricInfo& m) { return m.metric == metric; });
}

std::string Criterion::describe() const {
  // Streamed: GCC 12 warns falsely (-Wrestrict) about "literal" + std::string.
  std::ostringstream out;
  const MetricInfo& info = metricInfo(metric);
  if (metric == Metric::StaysBehind) {
    out << static_cast<char>('x' + axis) << " of " << body << (atLeast ? " >= " : " <= ");
  } else if (metric == Metric::Flips) {
    out << "flips of " << body;
    if (limit == upper)
      out << " = " << countText(limit);
    else if (std::isinf(upper))
      out << " >= " << countText(limit);
    else if (limit == 0.0)
      out << " <= " << countText(upper);
    else
      out << " from " << countText(limit) << " to " << countText(upper);
  } else {
    out << info.name;
    if (body == "*")
      out << " of every body";
    else if (!body.empty())
      out << " of " << body;
    out << " <= ";
  }
  if (metric != Metric::Flips) out << formatLimit(limit) << (*info.unit == '\0' ? "" : " ") << info.unit;
  out << " over " << formatNumber(from) << "-" << formatNumber(to) << " s";
  return out.str();
}

std::vector<Criterion> parseCriteria(const scenes::Scene& scene) {
  const std::string file = scene.file.empty() ? scene.name : scene.file.string();
  std::vector<Criterion> out;
  for (const scenes::Expectation& x : scene.expectations) {
    ExpectReader r(x, file, "<expect>");
    // The loader takes pass or position; position is an accuracy answer (accuracy.h), not ours.
    if (r.required("kind", "pass or position") != "pass") continue;
    out.push_back(parseOne(r, scene));
  }
  if (out.empty()) {
    throw scenes::LoadError(file, 0, "", "no <expect kind=\"pass\"> criterion: not a stability scene");
  }
  return out;
}

int runSteps(const std::vector<Criterion>& criteria) {
  int steps = 0;
  for (const Criterion& c : criteria) steps = std::max(steps, c.toStep);
  return steps;
}

double errorRatio(const Criterion& c, double value) {
  if (!std::isfinite(value)) return kInf;
  // A finite figure over a limit near 0 (max="1e-320") overflows the quotient; the largest double
  // fails as surely, and is not taken for a blow-up.
  const auto finite = [](double ratio) {
    return std::clamp(ratio, -std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
  };
  switch (c.metric) {
    case Metric::Flips: {
      // The nearer bound's ratio, oriented so that > 1 is outside: min / value, value / max; no
      // flip at all under a min is min / 0, infinite.
      const double low = c.limit <= 0.0 ? 0.0 : (value > 0.0 ? c.limit / value : kInf);
      return std::max(low, value / c.upper);
    }
    case Metric::StaysBehind:
      return finite((value - c.start) / (c.limit - c.start));
    default:
      return finite(value / c.limit);
  }
}

}  // namespace lab::stability
