#pragma once
// The lab's one progress bar, on stderr, for the commands that run many settings.
#include <chrono>
#include <cstddef>
#include <iosfwd>
#include <string>

namespace lab {

/// "sweep [#########.....................] 12/40 3 s pendulum xpbd 3x1". On a terminal the bar is
/// redrawn in place; anywhere else (a log, a test's string stream) it writes a line at each tenth
/// and where show() is asked to mark one, so a log keeps a few lines instead of a pile of \r.
class Progress {
 public:
  Progress(std::ostream& err, std::string name, std::size_t total);
  /// `done` runs have finished and `next` runs now; `mark`: a line in a log too (a scene done).
  void show(std::size_t done, const std::string& next = {}, bool mark = false);
  /// `runs` more have finished.
  void advance(std::size_t runs = 1) { show(done_ + runs); }
  /// Ends the redrawn line.
  void finish();

 private:
  std::ostream& err_;
  std::string name_;
  std::size_t total_;
  bool redraw_;
  std::chrono::steady_clock::time_point start_;
  std::size_t done_ = 0;
  std::size_t shownTenth_ = 0;
  std::size_t shownLength_ = 0;  ///< of the line on screen, so a shorter one can wipe it
};

}  // namespace lab
