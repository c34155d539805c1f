#include "stability_options.h"

#include <algorithm>
#include <cctype>
#include <optional>
#include <stdexcept>

#include "numbers.h"
#include "options.h"
#include "scenes/scene.h"
#include "text.h"

namespace lab::stability {
namespace {

// The list's items; a list with an empty item ("a,,b") reads as one empty item, which every
// parser below refuses by name ("unknown method ''").
std::vector<std::string> items(const std::string& text) {
  return lab::splitList(text).value_or(std::vector<std::string>{std::string()});
}

// A list of whole numbers from 1 to high; the error, or "" when good.
std::string parseCounts(const std::string& option, const std::string& text, int high,
                        std::vector<int>& into) {
  into.clear();
  for (const std::string& item : items(text)) {
    const std::optional<int> n = parseWholeNumber(item, 1, high);
    if (!n) return notWholeNumber(option, item, high);
    if (std::find(into.begin(), into.end(), *n) == into.end()) into.push_back(*n);
  }
  return {};
}

std::string parseMethods(const std::string& text, std::vector<phys::SolverMethod>& into) {
  into.clear();
  for (const std::string& item : items(text)) {
    const std::optional<phys::SolverMethod> m = phys::parseSolverMethod(item);
    if (!m) return "--methods: unknown method '" + item + "' (gauss-seidel, jacobi, xpbd or shake)";
    if (std::find(into.begin(), into.end(), *m) == into.end()) into.push_back(*m);
  }
  return {};
}

std::string parseModels(const std::string& text, std::vector<std::string>& into) {
  into.clear();
  for (const std::string& item : items(text)) {
    if (!phys::parseBodyModel(item))
      return "--models: unknown model '" + item + "' (corners, tetra or rigid)";
    if (std::find(into.begin(), into.end(), item) == into.end()) into.push_back(item);
  }
  return {};
}

std::filesystem::path suiteDirectory(const StabilityOptions& o) {
  RunOptions run;
  run.dataDir = o.dataDir;
  return scenes::sceneDirectory(dataDir(run)) / "stability";
}

}  // namespace

std::string usage() {
  return "usage: lab stability [--out DIR] [--methods LIST] [--iterations LIST] [--substeps LIST]\n"
         "                     [--models LIST] [--scene NAME...] [--sleep on|off] [--no-peers] [--data DIR]\n"
         "  Runs every scene of <data>/assets/scenes/stability under every method x model x iterations\n"
         "  x substeps, and in each peer engine, and judges each run by the scene's <expect kind=\"pass\">.\n"
         "  --out DIR         also write DIR/stability.md, .csv, .gp and the heat maps\n"
         "                    stability-pass.png/.svg and stability-error.png/.svg (gnuplot)\n"
         "  --methods LIST    comma-separated (default gauss-seidel,jacobi,xpbd,shake)\n"
         "  --iterations LIST whole numbers 1 to 1000 (default 1,3,10)\n"
         "  --substeps LIST   whole numbers 1 to 1000 (default 1,4,16)\n"
         "  --models LIST     corners, tetra or rigid, imposed on every box and ragdoll (ragdolls:\n"
         "                    seed, lean, rigid); default: each file's own\n"
         "  --scene NAME...   only these scenes: names in the suite's folder, or scene files\n"
         "                    (repeatable; comma-separated lists too)\n"
         "  --sleep on|off    whether islands at rest sleep, ours and the peers' (default off, whatever\n"
         "                    the scene says)\n"
         "  --no-peers        skip the peer engines\n"
         "  --data DIR        folder holding assets/ (default: the source tree)\n";
}

std::string parseOptions(const std::vector<std::string>& args, StabilityOptions& o) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&] { return optionValue(args, i); };
    std::string error;
    if (a == "--out" || a == "--data" || a == "--methods" || a == "--iterations" || a == "--substeps" ||
        a == "--models") {
      const std::string* v = value();
      if (v == nullptr) return a + " needs a value";
      if (a == "--out")
        o.out = *v;
      else if (a == "--data")
        o.dataDir = *v;
      else if (a == "--methods")
        error = parseMethods(*v, o.methods);
      else if (a == "--models")
        error = parseModels(*v, o.models);
      else if (a == "--iterations")
        error = parseCounts(a, *v, phys::kMaxIterations, o.iterations);
      else
        error = parseCounts(a, *v, phys::kMaxSubsteps, o.substeps);
    } else if (a == "--scene") {
      // Every following word up to the next option is a name, so "--scene a b" works too.
      const std::size_t before = o.scenes.size();
      while (const std::string* v = value()) {
        for (const std::string& name : items(*v)) {
          if (name.empty()) return "--scene: an empty name in '" + *v + "'";
          o.scenes.push_back(name);
        }
      }
      if (o.scenes.size() == before) return "--scene needs a scene name";
    } else if (a == "--sleep") {
      if (std::string e = parseOnOffOption(a, value(), o.sleep); !e.empty()) return e;
    } else if (a == "--no-peers") {
      o.peers = false;
    } else {
      return a.starts_with("-") ? "unknown option '" + a + "'"
                                : "unexpected argument '" + a + "' (scenes go after --scene)";
    }
    if (!error.empty()) return error;
  }
  return {};
}

bool naturalLess(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) && std::isdigit(static_cast<unsigned char>(b[j]))) {
      std::size_t ie = i, je = j;
      while (ie < a.size() && std::isdigit(static_cast<unsigned char>(a[ie]))) ++ie;
      while (je < b.size() && std::isdigit(static_cast<unsigned char>(b[je]))) ++je;
      const std::string na = a.substr(i, ie - i), nb = b.substr(j, je - j);
      if (na.size() != nb.size()) return na.size() < nb.size();
      if (na != nb) return na < nb;
      i = ie;
      j = je;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

std::vector<std::filesystem::path> sceneFiles(const StabilityOptions& o) {
  const std::filesystem::path folder = suiteDirectory(o);
  std::vector<std::filesystem::path> files;
  if (!o.scenes.empty()) {
    for (const std::string& name : o.scenes) {
      const std::filesystem::path file = scenes::resolveScene(name, folder);
      if (!std::filesystem::is_regular_file(file)) {
        throw std::runtime_error("--scene: no scene '" + name + "' (looked for " + file.string() + ")");
      }
      files.push_back(file);
    }
    return files;
  }
  if (!std::filesystem::is_directory(folder))
    throw std::runtime_error("no stability suite at " + folder.string());
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.is_regular_file() && entry.path().extension() == ".xml") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end(),
            [](const auto& a, const auto& b) { return naturalLess(a.stem().string(), b.stem().string()); });
  if (files.empty()) throw std::runtime_error("no scene files in " + folder.string());
  return files;
}

}  // namespace lab::stability
