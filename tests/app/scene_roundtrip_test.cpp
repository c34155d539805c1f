// The round trip as a property over generated scenes: every element and attribute of the format
// drawn at random within its documented range (docs/scene-format.md), loaded, stepped, saved,
// loaded again and compared with the world as it was saved (testsupport::compareScenes, whose
// tolerances say why each is what it is). A seed reproduces a scene; a failure prints its file.
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scenes/scene.h"
#include "scenes/scene_writer.h"
#include "world_compare.h"

namespace {

// One generated scene file, element by element, from a seed.
class SceneGenerator {
 public:
  explicit SceneGenerator(std::uint64_t seed) : random_(seed) {}

  std::string scene() {
    // Most scenes near the origin; some far out, where a coordinate keeps fewer digits.
    far_ = chance(0.15);
    origin_ = far_ ? vector(-8e5, 8e5) : Vec(0.0, 0.0, 0.0);
    std::string xml =
        "<scene name=\"generated\" description=\"" + pick({"", "a, b &amp; &lt;c&gt;", "line"}) + "\">\n";
    if (chance(0.8)) xml += world();
    if (chance(0.8)) xml += solver();
    if (chance(0.7)) xml += ground();
    if (chance(0.5)) xml += camera();
    const int elements = integer(1, 8);
    for (int i = 0; i < elements; ++i) xml += body();
    // Joints and filters between what exists, in any order after the bodies they name.
    for (int i = integer(0, 4); i > 0; --i) xml += link();
    for (int i = integer(0, 2); i > 0; --i) xml += noCollision();
    for (int i = integer(0, 2); i > 0; --i) xml += stick();
    return xml + "</scene>\n";
  }

 private:
  struct Vec {
    double x, y, z;
    Vec(double a, double b, double c) : x(a), y(b), z(c) {}
  };

  bool chance(double p) { return std::uniform_real_distribution<double>(0.0, 1.0)(random_) < p; }
  double real(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(random_); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(random_); }
  std::string pick(std::initializer_list<const char*> options) {
    return *(options.begin() + integer(0, static_cast<int>(options.size()) - 1));
  }
  Vec vector(double lo, double hi) { return {real(lo, hi), real(lo, hi), real(lo, hi)}; }

  static std::string num(double v) {
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.17g", v);
    return buffer;
  }
  static std::string vec(const Vec& v) { return num(v.x) + " " + num(v.y) + " " + num(v.z); }
  // XML-escaped, so names with markup in them reach the loader as written.
  static std::string attr(const std::string& name, const std::string& value) {
    std::string out = " " + name + "=\"";
    for (char c : value) {
      if (c == '&')
        out += "&amp;";
      else if (c == '<')
        out += "&lt;";
      else if (c == '"')
        out += "&quot;";
      else
        out += c;
    }
    return out + "\"";
  }
  // A position near the scene's origin, above the ground.
  Vec place(double spread = 6.0) {
    return {origin_.x + real(-spread, spread), origin_.y + real(0.5, spread),
            origin_.z + real(-spread, spread)};
  }

  std::string world() {
    std::string e = "  <world";
    if (chance(0.7)) e += attr("gravity", vec(vector(-12.0, 12.0)));
    if (chance(0.2)) {
      e += attr("gravity-mode", "point") + attr("gravity-point", vec(place())) +
           attr("gravity-strength", num(real(0.0, 20.0)));
    }
    if (chance(0.4)) e += attr("damping", num(real(0.0, 2.0)));
    if (chance(0.3)) e += attr("bound", far_ ? "1e6" : num(real(100.0, 1e9)));
    return e + "/>\n";
  }

  std::string solver() {
    std::string e = "  <solver";
    if (chance(0.8)) e += attr("method", pick({"gauss-seidel", "jacobi", "xpbd", "shake"}));
    if (chance(0.7)) e += attr("iterations", std::to_string(integer(1, 6)));
    if (chance(0.7)) e += attr("substeps", std::to_string(integer(1, 4)));
    if (chance(0.5)) e += attr("dt", num(real(1.0 / 240.0, 1.0 / 30.0)));
    if (chance(0.3)) e += attr("epsilon", num(real(0.0, 0.05)));
    if (chance(0.3)) e += attr("slop", num(real(0.0, 0.01)));
    if (chance(0.3)) e += attr("body-damping", num(real(0.0, 1.0)));
    if (chance(0.3)) e += attr("keep-spin", chance(0.5) ? "on" : "off");
    if (chance(0.3)) e += attr("restitution", num(real(0.0, 1.0)));
    if (chance(0.3)) e += attr("compliance", num(real(0.0, 1e-3)));
    if (chance(0.3)) e += attr("depenetration-speed", chance(0.5) ? "none" : num(real(0.1, 10.0)));
    if (chance(0.3)) e += attr("sleep", chance(0.5) ? "on" : "off");
    if (chance(0.2)) e += attr("threads", std::to_string(integer(1, 4)));
    if (chance(0.2)) e += attr("sleep-speed", num(real(0.0, 0.2)));
    if (chance(0.2)) e += attr("sleep-time", num(real(0.0, 2.0)));
    if (chance(0.3)) e += attr("joint-projection", chance(0.5) ? "on" : "off");
    if (chance(0.2)) e += attr("projection-tolerance", num(real(1e-6, 1e-2)));
    if (chance(0.2)) e += attr("projection-iterations", std::to_string(integer(1, 8)));
    return e + "/>\n";
  }

  std::string ground() {
    std::string e = "  <ground" + attr("height", num(origin_.y + real(-0.5, 0.5)));
    if (chance(0.4)) e += attr("normal", vec({real(-0.3, 0.3), 1.0, real(-0.3, 0.3)}));
    if (chance(0.5)) e += attr("friction", num(real(0.0, 1.0)));
    if (chance(0.3)) e += attr("static-friction", num(real(0.0, 1.0)));
    return e + "/>\n";
  }

  std::string camera() {
    const Vec eye = place(10.0);
    return "  <camera" + attr("eye", vec(eye)) +
           attr("target", vec({eye.x + 1.0, eye.y - 1.0, eye.z - 3.0})) + "/>\n";
  }

  std::string name(const char* kind) {
    std::string n = std::string(kind) + " " + std::to_string(count_++);
    if (chance(0.1)) n += " \"&'<>";  // markup in a name must come back unchanged
    return n;
  }

  // What box-like elements share: size or radius/length, mass, model, friction, orientation.
  std::string bodyCommon(bool capsule) {
    std::string e;
    if (capsule) {
      const double radius = real(0.05, 0.5);
      e += attr("radius", num(radius)) + attr("length", num(2.0 * radius + real(0.0, 1.5)));
    } else if (chance(0.7)) {
      e += attr("size", chance(0.5) ? num(real(0.05, 2.0)) : vec(vector(0.05, 2.0)));
    }
    if (chance(0.6)) e += attr("mass", num(std::exp(real(std::log(0.01), std::log(1000.0)))));
    if (chance(0.5)) e += attr("model", pick({"corners", "tetra"}));
    if (chance(0.3)) e += attr("friction", num(real(0.0, 1.2)));
    if (chance(0.6)) e += attr("euler", vec(vector(-180.0, 180.0)));
    return e;
  }

  std::string body() {
    switch (integer(0, 8)) {
      case 0: {
        const std::string n = name("p");
        particles_.push_back(n);
        std::string e = "  <particle" + attr("name", n) + attr("pos", vec(place()));
        if (chance(0.5)) e += attr("velocity", vec(vector(-5.0, 5.0)));
        if (chance(0.5)) e += attr("mass", num(real(0.1, 10.0)));
        if (chance(0.2)) e += attr("pinned", "true");
        return e + "/>\n";
      }
      case 1:
      case 2: {
        const bool capsule = chance(0.4);
        const std::string n = name(capsule ? "c" : "b");
        bodies_.push_back(n);
        std::string e = std::string(capsule ? "  <capsule" : "  <box") + attr("name", n) +
                        attr("pos", vec(place())) + bodyCommon(capsule);
        if (chance(0.5)) e += attr("velocity", vec(vector(-5.0, 5.0)));
        if (chance(0.4)) e += attr("angular-velocity", vec(vector(-360.0, 360.0)));
        if (chance(0.2))
          e += attr("group", std::to_string(integer(0, 7))) + attr("mask", std::to_string(integer(0, 255)));
        return e + "/>\n";
      }
      case 3:
        return generator("stack", attr("count", std::to_string(integer(1, 5))));
      case 4:
        return generator("pyramid", attr("base", std::to_string(integer(1, 4))) +
                                        (chance(0.5) ? attr("taper", num(real(0.5, 1.0))) : ""));
      case 5:
        return generator(
            "grid", attr("count", std::to_string(integer(1, 3)) + " " + std::to_string(integer(1, 2)) + " " +
                                      std::to_string(integer(1, 3))) +
                        (chance(0.5) ? attr("spacing", num(real(1.0, 2.5))) : ""));
      case 6: {
        const std::string n = name("chain");
        const int links = integer(1, 6);
        for (int i = 0; i <= links; ++i) particles_.push_back(n + "[" + std::to_string(i) + "]");
        std::string e = "  <chain" + attr("name", n) + attr("pos", vec(place())) +
                        attr("links", std::to_string(links)) + attr("length", num(real(0.1, 1.0)));
        if (chance(0.4)) e += attr("end-mass", num(real(0.5, 50.0)));
        if (chance(0.3)) e += attr("pinned", "false");
        if (chance(0.3)) e += attr("compliance", num(real(0.0, 1e-3)));
        if (chance(0.4)) e += attr("direction", vec(vector(-1.0, 1.0)));
        return e + "/>\n";
      }
      default: {
        const std::string n = name("r");
        const bool capsules = chance(0.5);
        static const char* kBoxParts[] = {"head", "torso", "upper-arm-left", "lower-arm-right",
                                          "upper-leg-left"};
        static const char* kCapsuleParts[] = {"head", "pelvis", "spine", "upper-arm-left", "lower-leg-right"};
        for (const char* part : capsules ? kCapsuleParts : kBoxParts) bodies_.push_back(n + "." + part);
        std::string e = "  <ragdoll" + attr("name", n) + attr("pos", vec(place())) +
                        attr("shape", capsules ? "capsule" : "box");
        if (chance(0.5)) e += attr("euler", vec(vector(-180.0, 180.0)));
        if (chance(0.4)) e += attr("scale", num(real(0.3, 2.0)));
        if (chance(0.4)) e += attr("mass", num(real(5.0, 120.0)));
        if (chance(0.5)) e += attr("model", pick({"seed", "lean"}));
        if (chance(0.4)) e += attr("velocity", vec(vector(-4.0, 4.0)));
        if (chance(0.3)) e += attr("joint-damping", num(real(0.0, 5.0)));
        return e + "/>\n";
      }
    }
  }

  std::string generator(const char* kind, const std::string& own) {
    const std::string n = name(kind);
    bodies_.push_back(n + "[0]");  // every generator makes at least one box
    return "  <" + std::string(kind) + attr("name", n) + attr("pos", vec(place(4.0))) + own +
           bodyCommon(false) + "/>\n";
  }

  // A link between two named bodies, a pin or a range, with one point or one for each end.
  std::string link() {
    std::vector<std::string> ends = bodies_;
    ends.insert(ends.end(), particles_.begin(), particles_.end());
    if (ends.size() < 2) return {};
    const std::string a = ends[static_cast<std::size_t>(integer(0, static_cast<int>(ends.size()) - 1))];
    const std::string b = ends[static_cast<std::size_t>(integer(0, static_cast<int>(ends.size()) - 1))];
    if (a == b) return {};
    std::string e = "  <link" + attr("a", a) + attr("b", b);
    if (chance(0.5)) {
      e += attr("point", vec(place()));
    } else {
      e += attr("a-point", vec(place())) + attr("b-point", vec(place()));
    }
    const int kind = integer(0, 3);  // a pin, a min, a max, or both
    const double min = real(0.0, 1.0);
    if (kind == 1 || kind == 3) e += attr("min", num(min));
    if (kind == 2 || kind == 3) e += attr("max", num(min + real(0.01, 2.0)));
    return e + "/>\n";
  }

  std::string noCollision() {
    if (bodies_.size() < 2) return {};
    const std::string a = bodies_[static_cast<std::size_t>(integer(0, static_cast<int>(bodies_.size()) - 1))];
    const std::string b = bodies_[static_cast<std::size_t>(integer(0, static_cast<int>(bodies_.size()) - 1))];
    if (a == b) return {};
    return "  <no-collision" + attr("a", a) + attr("b", b) + "/>\n";
  }

  std::string stick() {
    if (particles_.size() < 2) return {};
    const std::string a =
        particles_[static_cast<std::size_t>(integer(0, static_cast<int>(particles_.size()) - 1))];
    const std::string b =
        particles_[static_cast<std::size_t>(integer(0, static_cast<int>(particles_.size()) - 1))];
    if (a == b) return {};
    std::string e = "  <stick" + attr("a", a) + attr("b", b);
    switch (integer(0, 3)) {
      case 0:
        break;  // auto: the particles are never generated on top of each other
      case 1:
        e += attr("length", num(real(0.1, 3.0)));
        break;
      case 2:
        e += attr("min", num(real(0.0, 1.0)));
        break;
      default:
        e += attr("max", num(real(0.5, 3.0)));
    }
    if (chance(0.3)) e += attr("compliance", num(real(0.0, 1e-2)));
    return e + "/>\n";
  }

  std::mt19937_64 random_;
  bool far_ = false;
  Vec origin_{0.0, 0.0, 0.0};
  int count_ = 0;
  std::vector<std::string> bodies_, particles_;
};

// Generated scenes: how many loaded (some draws are refused, e.g. bodies generated overlapping a
// chain's particle at one spot give an auto stick of length 0), and each one's round trip.
TEST(SceneRoundTrip, GeneratedScenesSaveAndReloadAsTheSameWorld) {
  constexpr int kScenes = 300;
  int loaded = 0, stepped = 0;
  for (int seed = 1; seed <= kScenes; ++seed) {
    SceneGenerator generate(static_cast<std::uint64_t>(seed));
    const std::string xml = generate.scene();
    std::optional<scenes::Scene> scene;
    try {
      scene.emplace(scenes::loadSceneText(xml, "generated.xml"));
    } catch (const scenes::LoadError& e) {
      // Refusals are fine only where a generated draw breaks a documented rule.
      const std::string why = e.what();
      EXPECT_TRUE(why.find("auto needs the particles apart") != std::string::npos ||
                  why.find("is already the name") != std::string::npos)
          << "seed " << seed << ": " << why << "\n"
          << xml;
      continue;
    }
    ++loaded;
    const int steps = static_cast<int>(static_cast<std::uint64_t>(seed) * 7919 % 40);
    for (int i = 0; i < steps; ++i) scene->world.step();
    stepped += steps > 0;
    std::string saved;
    try {
      saved = scenes::writeSceneXml(*scene);
    } catch (const std::invalid_argument& e) {
      // Only a link whose end a particle is joined to itself through a box can be refused.
      ADD_FAILURE() << "seed " << seed << ": not saved: " << e.what() << "\n" << xml;
      continue;
    }
    try {
      const scenes::Scene reloaded = scenes::loadSceneText(saved, "saved.xml");
      const std::string difference = testsupport::compareScenes(*scene, reloaded);
      EXPECT_EQ(difference, "") << "seed " << seed << " after " << steps << " steps\n" << xml;
    } catch (const scenes::LoadError& e) {
      ADD_FAILURE() << "seed " << seed << ": the saved scene does not reload: " << e.what() << "\n"
                    << xml << "\nsaved:\n"
                    << saved;
    }
  }
  // The generator must mostly make scenes that load, or the property is tested on nothing.
  EXPECT_GT(loaded, kScenes * 8 / 10);
  EXPECT_GT(stepped, loaded * 8 / 10);
}

}  // namespace
