#include "options.h"

#include <algorithm>
#include <charconv>
#include <limits>
#include <optional>
#include <set>
#include <system_error>

#include "fileio/files.h"
#include "fileio/printable.h"
#include "open_scene.h"
#include "scenes/scene.h"

namespace sandbox {
namespace {

constexpr int kMaxFrames = 1000000;
// An argument longer than this is shown in a message by its start and its length: a 100 kB value
// pasted by mistake would otherwise fill the terminal and hide what is wrong with it. Paths and
// overlay settings of any use are far shorter.
constexpr std::size_t kLongArgument = 1024;
constexpr std::size_t kShownStart = 60;

// A whole number from min to max written as nothing else, or nothing.
std::optional<long> wholeNumber(const std::string& text, long min, long max) {
  long n = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
  if (ec != std::errc() || end != text.data() + text.size() || n < min || n > max) return std::nullopt;
  return n;
}

// "all", or names of kSectionNames separated by commas, each once at most.
std::optional<SectionFlags> parseSections(const std::string& text) {
  SectionFlags open{};
  if (text == "all") {
    open.fill(true);
    return open;
  }
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string name = text.substr(start, comma - start);
    const auto* found =
        std::find_if(kSectionNames.begin(), kSectionNames.end(), [&](const char* n) { return name == n; });
    if (found == kSectionNames.end()) return std::nullopt;
    open[static_cast<std::size_t>(found - kSectionNames.begin())] = true;
    start = comma + 1;
  }
  return open;
}

// A long argument as its first bytes (never cutting a UTF-8 character) and its length.
std::string shortened(const std::string& arg) {
  std::size_t cut = kShownStart;
  while (cut > 0 && (static_cast<unsigned char>(arg[cut]) & 0xC0U) == 0x80U) --cut;
  return arg.substr(0, cut) + "... (" + std::to_string(arg.size()) + " bytes)";
}

// The message as it can be printed: every long argument it quotes shortened, every control
// character escaped. Done once on the finished message, so that every message, the overlay's own
// among them, is shown the same way.
std::string printable(std::string error, const std::vector<std::string>& args) {
  for (const std::string& arg : args) {
    if (arg.size() <= kLongArgument) continue;
    const std::string shown = shortened(arg);
    for (std::size_t at = error.find(arg); at != std::string::npos; at = error.find(arg, at + shown.size()))
      error.replace(at, arg.size(), shown);
  }
  // Control characters as \xNN: a value holding an escape sequence must not drive the terminal the
  // message is printed on, and a newline in it must not pass for the end of the message.
  return fileio::printableReason(error, std::numeric_limits<std::size_t>::max());
}

// The options without a value: given twice, they say the same thing twice.
const std::set<std::string> kFlags = {"--markers", "--trails",      "--targets", "--no-shadows",
                                      "--sweep",   "--hide-panels", "--help"};

// "--" alone, or "--" and a name: where an option goes, not a value.
bool isOption(const std::string& arg) {
  return arg.size() >= 2 && arg.compare(0, 2, "--") == 0;
}

}  // namespace

std::string usage() {
  return "usage: sandbox [SCENE] [--screenshot FILE --frames N] [--draw MODE] [--markers] [--trails] "
         "[--targets]\n"
         "               [--color-by WHAT] [--threads N] [--overlay SETTINGS...] [--pause-at N]\n"
         "               [--hide-panels] [--unfold SECTIONS] [--no-shadows] [--sweep] [--data DIR]\n"
         "  SCENE              a scene file, or the name of one in assets/scenes/ (default: the\n"
         "                     scene open when the sandbox last closed, else ragdoll; a\n"
         "                     screenshot's is always ragdoll)\n"
         "  --screenshot FILE  render N frames, write the last to FILE as PNG and exit\n"
         "  --frames N         frames before the screenshot, 1 to 1000000 (default 60);\n"
         "                     each frame advances the simulation by one step\n"
         "  --draw MODE        filled, wireframe or constraints (default: the last one used)\n"
         "  --markers          green boxes on vertices moved by box-box contacts (key C)\n"
         "  --trails           the paths of loose particles and of the followed body\n"
         "  --targets          each character's target pose as a ghost\n"
         "  --no-shadows       no shadows of the bodies on the ground (Draw > shadows)\n"
         "  --sweep            start the Lab section's sweep of the scene at once, and unfold it\n"
         "  --color-by WHAT    kind, body, island or sleep: what bodies' colours say (default body)\n"
         "  --threads N        threads the step may use, 1 to 64, in every scene opened\n"
         "                     (default: each scene's own, else 1)\n"
         "  --overlay S1 S2..  run the scene under 2 to 4 solver settings at once, each drawn\n"
         "                     translucent in its own colour; each S is key=value,... with\n"
         "                     <solver>'s names, e.g. --overlay iterations=3 substeps=8 method=xpbd\n"
         "  --pause-at N       pause after step N (0 to 1000000)\n"
         "  --hide-panels      start with the panels hidden: the scene fills the window (key F2)\n"
         "  --unfold SECTIONS  the panels' sections open at the start, comma-separated, of\n"
         "                     simulation, rewind, world, draw, stats, lab, or all (default\n"
         "                     simulation,rewind,stats)\n"
         "  --data DIR         folder holding shaders/ and assets/ (default: the source tree)\n"
         "  --help             show this text\n"
         "  --                 ends the options: the scene may follow, whatever it starts with\n";
}

namespace {

// The arguments as given; the error quotes them unshortened (parseOptions makes it printable).
ParsedOptions parseArguments(const std::vector<std::string>& args) {
  ParsedOptions out;
  Options& o = out.options;
  bool framesGiven = false;
  bool optionsEnded = false;        // after "--" every argument is the scene
  std::set<std::string> givenOnce;  // options with a value: a second one would silently win
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (!optionsEnded && a == "--") {
      optionsEnded = true;
      continue;
    }
    if (!optionsEnded && isOption(a) && kFlags.count(a) == 0 && !givenOnce.insert(a).second) {
      out.error = a + " is given twice; give it once";
      return out;
    }
    // The option's value, or nullptr with the error set. An option in its place is refused rather
    // than taken as the value: `--screenshot --hide-panels` wrote a PNG named "--hide-panels".
    auto value = [&](const char* what) -> const std::string* {
      if (i + 1 >= args.size()) {
        out.error = a + " needs " + what;
        return nullptr;
      }
      const std::string& next = args[i + 1];
      if (isOption(next)) {
        out.error = a + " needs " + what + ", and '" + next + "' " +
                    (next == "--" ? "ends the options" : "is an option");
        if (a == "--screenshot" || a == "--data") out.error += " (one of that name is ./" + next + ")";
        return nullptr;
      }
      return &args[++i];
    };
    // The option's value as a whole number from min to max, or nullopt with the error set.
    auto number = [&](const char* what, long min, long max) -> std::optional<long> {
      const std::string* v = value(what);
      if (v == nullptr) return std::nullopt;
      const std::optional<long> n = wholeNumber(*v, min, max);
      if (!n) {
        out.error = a + ": '" + *v + "' is not a whole number from " + std::to_string(min) + " to " +
                    std::to_string(max);
      }
      return n;
    };
    if (optionsEnded || a.empty() || a[0] != '-' || a == "-") {
      if (a.empty()) {
        out.error = "the scene's name is empty";
        return out;
      }
      if (!o.scene.empty()) {
        out.error = "one scene only; got '" + o.scene + "' and '" + a + "'";
        return out;
      }
      o.scene = a;
    } else if (a == "--help" || a == "-h") {
      o.help = true;
    } else if (a == "--screenshot") {
      const std::string* v = value("a file name");
      if (v == nullptr) return out;
      if (v->empty()) {
        out.error = "--screenshot: the file name is empty";
        return out;
      }
      o.screenshot = *v;
    } else if (a == "--frames") {
      const std::optional<long> n = number("a number of frames", 1, kMaxFrames);
      if (!n) return out;
      o.frames = static_cast<int>(*n);
      framesGiven = true;
    } else if (a == "--draw") {
      const std::string* v = value("filled, wireframe or constraints");
      if (v == nullptr) return out;
      o.draw = parseDrawMode(*v);
      if (!o.draw) {
        out.error = "--draw: '" + *v + "' must be filled, wireframe or constraints";
        return out;
      }
    } else if (a == "--markers") {
      o.markers = true;
    } else if (a == "--trails") {
      o.trails = true;
    } else if (a == "--targets") {
      o.targets = true;
    } else if (a == "--no-shadows") {
      o.noShadows = true;
    } else if (a == "--sweep") {
      o.sweep = true;
    } else if (a == "--hide-panels") {
      o.hidePanels = true;
    } else if (a == "--unfold") {
      const std::string* v = value("sections");
      if (v == nullptr) return out;
      o.unfold = parseSections(*v);
      if (!o.unfold) {
        out.error = "--unfold: '" + *v +
                    "' must be all, or sections among simulation, rewind, world, draw, stats, lab";
        return out;
      }
    } else if (a == "--threads") {
      const std::optional<long> n = number("a whole number from 1 to 64", 1, phys::kMaxThreads);
      if (!n) return out;
      o.threads = static_cast<int>(*n);
    } else if (a == "--color-by") {
      const std::string* v = value("kind, body, island or sleep");
      if (v == nullptr) return out;
      o.coloring = parseBodyColoring(*v);
      if (!o.coloring) {
        out.error = "--color-by: '" + *v + "' must be kind, body, island or sleep";
        return out;
      }
    } else if (a == "--overlay") {
      // Every following argument that is not an option is one run's settings.
      while (i + 1 < args.size() &&
             !(args[i + 1].size() > 1 && args[i + 1][0] == '-' && args[i + 1][1] == '-')) {
        if (args[i + 1].size() > kLongArgument) {  // its messages quote a part of it, not shortened
          out.error = "--overlay: '" + args[i + 1] + "' is longer than a setting can be (" +
                      std::to_string(kLongArgument) + " bytes)";
          return out;
        }
        const ParsedOverlaySpec parsed = parseOverlaySpec(args[++i]);
        if (!parsed.error.empty()) {
          out.error = "--overlay: " + parsed.error;
          // With no scene yet, a plain word with no '=' is most likely the scene, written after
          // the settings took over.
          const std::string& word = args[i];
          if (o.scene.empty() && !word.empty() && word.find('=') == std::string::npos && word.front() != '-')
            out.error += " (a scene goes before --overlay)";
          return out;
        }
        o.overlay.push_back(parsed.spec);
      }
      if (o.overlay.size() < static_cast<std::size_t>(kMinOverlayRuns) ||
          o.overlay.size() > static_cast<std::size_t>(kMaxOverlayRuns)) {
        out.error = "--overlay needs " + std::to_string(kMinOverlayRuns) + " to " +
                    std::to_string(kMaxOverlayRuns) + " settings, got " + std::to_string(o.overlay.size());
        return out;
      }
    } else if (a == "--pause-at") {
      o.pauseAt = number("a step number", 0, kMaxFrames);
      if (!o.pauseAt) return out;
    } else if (a == "--data") {
      const std::string* v = value("a folder");
      if (v == nullptr) return out;
      if (v->empty()) {  // it would mean the default folder, which no --data is the way to say
        out.error = "--data: the folder name is empty";
        return out;
      }
      o.dataDir = *v;
    } else {
      out.error = "unknown option '" + a + "'";
      return out;
    }
  }
  if (framesGiven && !o.screenshot) out.error = "--frames needs --screenshot FILE";
  return out;
}

}  // namespace

ParsedOptions parseOptions(const std::vector<std::string>& args) {
  ParsedOptions out = parseArguments(args);
  if (!out.error.empty()) out.error = printable(out.error, args);
  return out;
}

namespace {

std::string dataDirProblem(const std::filesystem::path& folder) {
  if (std::string why = fileio::folderProblem(folder); !why.empty())
    return "--data '" + folder.string() + "': " + why;
  for (const char* inside : {"shaders", "assets"}) {
    if (std::string why = fileio::folderProblem(folder / inside); !why.empty())
      return "--data '" + folder.string() + "': its " + inside + "/ folder: " + why;
  }
  return {};
}

// Opened here as the sandbox opens it, before a window does; `scene` is left null on failure.
std::string sceneProblem(const Options& options, std::unique_ptr<scenes::Scene>& scene) {
  const std::filesystem::path file = scenePath(options);
  try {
    fileio::checkRegularFile(file, "scene file");
    scene = loadCheckedScene(file, sceneLoadOptions(options.threads));
  } catch (const std::exception& e) {  // fileio::FileError, scenes::LoadError: each names the file
    return std::string("scene: ") + e.what();
  }
  return {};
}

// The screenshot is written at the end of the run: a name it cannot have is said at the start.
std::string screenshotProblem(const std::filesystem::path& file) {
  const std::filesystem::path folder = file.has_parent_path() ? file.parent_path() : ".";
  if (std::string why = fileio::folderProblem(folder); !why.empty())
    return "--screenshot '" + file.string() + "': its folder '" + folder.string() + "': " + why;
  std::error_code ec;  // a file not there yet is the usual case; anything else (a name too long) is said
  const std::filesystem::file_status status = std::filesystem::status(file, ec);
  if (std::filesystem::is_directory(status)) return "--screenshot '" + file.string() + "': is a folder";
  if (ec && ec != std::errc::no_such_file_or_directory)
    return "--screenshot '" + file.string() + "': " + ec.message();
  return {};
}

}  // namespace

CheckedFiles checkFiles(const Options& options) {
  CheckedFiles out;
  std::string& error = out.error;
  if (!options.dataDir.empty()) error = dataDirProblem(options.dataDir);
  if (error.empty() && !options.scene.empty()) error = sceneProblem(options, out.scene);
  if (error.empty() && options.screenshot) error = screenshotProblem(*options.screenshot);
  const std::vector<std::string> named = {options.scene, options.dataDir.string(),
                                          options.screenshot.value_or("").string()};
  error = printable(error, named);
  if (!error.empty()) out.scene.reset();
  return out;
}

std::filesystem::path dataDir(const Options& options) {
  return options.dataDir.empty() ? std::filesystem::path(SANDBOX_DATA_DIR) : options.dataDir;
}

std::filesystem::path scenePath(const Options& options) {
  const std::string_view name =
      options.scene.empty() ? scenes::kDefaultScene : std::string_view(options.scene);
  return scenes::resolveScene(name, scenes::sceneDirectory(dataDir(options)));
}

}  // namespace sandbox
