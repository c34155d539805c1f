#include "expect_reader.h"

#include <algorithm>
#include <utility>

#include "bodies.h"
#include "text.h"

namespace lab {

std::optional<std::size_t> bodySlot(const scenes::Scene& scene, const std::string& name) {
  for (const scenes::NamedBody& b : scene.bodies) {
    if (b.name != name) continue;
    if (b.kind == scenes::NamedBody::Kind::Body) return b.index;
    const std::vector<phys::ParticleId> loose = looseParticles(scene.world);
    const auto it = std::lower_bound(loose.begin(), loose.end(), b.particle());
    if (it == loose.end() || *it != b.particle()) return std::nullopt;  // a box's: the list holds its box
    return scene.world.bodies().size() + static_cast<std::size_t>(it - loose.begin());
  }
  return std::nullopt;
}

ExpectReader::ExpectReader(const scenes::Expectation& x, std::string file, std::string element)
    : x_(x), file_(std::move(file)), element_(std::move(element)) {}

void ExpectReader::fail(const std::string& attribute, const std::string& message) const {
  throw scenes::LoadError(file_, x_.line, attribute, element_ + " attribute '" + attribute + "': " + message);
}

const std::string* ExpectReader::find(const std::string& name) {
  asked_.push_back(name);
  return x_.find(name);
}

const std::string& ExpectReader::required(const std::string& name, const std::string& what) {
  const std::string* v = find(name);
  if (v == nullptr) fail(name, what.empty() ? "is required" : "is required (" + what + ")");
  return *v;
}

void ExpectReader::rejectUnknown(const std::string& scope) const {
  for (std::size_t i = 0; i < x_.attributes.size(); ++i) {
    const std::string& name = x_.attributes[i].first;
    if (std::find(asked_.begin(), asked_.end(), name) == asked_.end()) {
      fail(name, "unknown attribute" + scope + " (known: " + join(asked_, ", ") + ")");
    }
    for (std::size_t j = i + 1; j < x_.attributes.size(); ++j) {
      if (x_.attributes[j].first == name) fail(name, "given twice");
    }
  }
}

}  // namespace lab
