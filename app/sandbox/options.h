#pragma once
// The sandbox's command line:
//   sandbox [SCENE] [--screenshot FILE --frames N] [--draw filled|wireframe|constraints]
//           [--markers] [--trails] [--targets] [--color-by WHAT] [--threads N] [--overlay SETTINGS...]
//           [--pause-at N] [--hide-panels] [--unfold SECTIONS] [--no-shadows] [--sweep]
//           [--data DIR] [--help] [-- SCENE]
#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "draw_options.h"
#include "overlay_spec.h"
#include "scenes/scene.h"

namespace sandbox {

/// The panels' column's sections, in its order (--unfold names them so).
inline constexpr std::array<const char*, 6> kSectionNames = {"simulation", "rewind", "world",
                                                             "draw",       "stats",  "lab"};
using SectionFlags = std::array<bool, kSectionNames.size()>;

struct Options {
  std::string scene;  ///< a scene file, or a name in assets/scenes/; empty: the default scene
  std::optional<std::filesystem::path> screenshot;  ///< render, write this PNG, exit
  int frames = 60;                ///< frames rendered before the screenshot; one physics step each
  std::filesystem::path dataDir;  ///< holds shaders/ and assets/; empty: the build's default
  std::optional<DrawMode> draw;   ///< given: overrides the remembered draw mode
  bool markers = false;           ///< the seed's collision-vertex markers from the start
  bool trails = false;            ///< Draw > trails from the start
  bool targets = false;           ///< Draw > target poses from the start
  bool noShadows = false;         ///< no shadows on the ground (the rendering tests read ground pixels)
  bool sweep = false;             ///< start the Lab section's sweep of the scene at once, and unfold it
  bool hidePanels = false;        ///< the side column hidden from the start (F2 shows it)
  /// Which of the column's sections (kSectionNames' order) start unfolded; none given: Simulation,
  /// Rewind and Stats.
  std::optional<SectionFlags> unfold;
  std::optional<BodyColoring> coloring;  ///< given: what bodies' colours say from the start
  std::optional<int> threads;            ///< given: the threads every scene opened steps with
  std::vector<OverlaySpec> overlay;      ///< 2 to 4 runs of the method overlay, or none
  std::optional<long> pauseAt;           ///< pause when the main run has taken this many steps
  bool help = false;
};

struct ParsedOptions {
  Options options;
  std::string error;  ///< empty on success; otherwise what is wrong with which argument
};

/// The options in `args` (argv without the program), or what is wrong with which argument; a value
/// the error quotes has its control characters escaped and, past 1024 bytes, only its start shown.
ParsedOptions parseOptions(const std::vector<std::string>& args);
struct CheckedFiles {
  std::string error;                     ///< "" when nothing is wrong
  std::unique_ptr<scenes::Scene> scene;  ///< the scene named, as the sandbox opens it; null if none
};
/// What is wrong with the files and folders the options name, in the OS's words and naming the
/// option: a scene that is no readable file or does not open as the sandbox opens it
/// (loadCheckedScene), a --data that is no folder with shaders/ and assets/ in it, a --screenshot that
/// is a folder or whose folder is missing. Checked before a window opens, so that a mistyped name
/// is said without a display; the scene opened for it is kept, for the sandbox to start with.
CheckedFiles checkFiles(const Options& options);
/// The usage text printed by --help and after an error.
std::string usage();
/// The folder holding shaders/ and assets/: options.dataDir, or the one set at build time.
std::filesystem::path dataDir(const Options& options);
/// The scene file to open: options.scene as a path or a name in assets/scenes/, else the default.
std::filesystem::path scenePath(const Options& options);

}  // namespace sandbox
