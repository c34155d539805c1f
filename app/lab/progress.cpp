#include "progress.h"

#include <unistd.h>

#include <algorithm>
#include <iostream>
#include <utility>

namespace lab {

Progress::Progress(std::ostream& err, std::string name, std::size_t total)
    : err_(err),
      name_(std::move(name)),
      total_(total),
      redraw_(&err == &std::cerr && ::isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()) {}

void Progress::show(std::size_t done, const std::string& next, bool mark) {
  done_ = done;
  const std::size_t tenth = total_ == 0 ? 10 : 10 * std::min(done, total_) / total_;
  if (!redraw_ && !mark && tenth <= shownTenth_) return;
  shownTenth_ = std::max(shownTenth_, tenth);
  constexpr std::size_t kWidth = 30;
  const std::size_t filled = total_ == 0 ? kWidth : kWidth * std::min(done, total_) / total_;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::string line = name_ + " [" + std::string(filled, '#') + std::string(kWidth - filled, '.') + "] " +
                     std::to_string(done) + "/" + std::to_string(total_) + " " +
                     std::to_string(static_cast<long>(seconds)) + " s" + (next.empty() ? "" : " " + next);
  if (!redraw_) {
    err_ << line << "\n" << std::flush;
    return;
  }
  const std::size_t length = line.size();
  line.resize(std::max(length, shownLength_), ' ');  // wipes what a longer previous line left
  shownLength_ = length;
  err_ << "\r" << line << std::flush;
}

void Progress::finish() {
  if (redraw_) err_ << "\n" << std::flush;
}

}  // namespace lab
