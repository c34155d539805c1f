#pragma once
// The soak test's memory rules, both taken right after a project scene is opened afresh: at
// that moment the whole world has just been replaced, and the overlays, thrown bodies and
// broad-phase pairs of earlier episodes are gone, so whatever memory the run still holds beyond
// one scene's world is a leak.
//
// 1. The resident set size (/proc/self/statm), at most every kRssSampleSeconds, after handing
//    freed memory back to the system (malloc_trim): glibc otherwise keeps up to 64 MiB of freed
//    heap mapped by its dynamic thresholds, which would hide a leak of that size or fake one.
//    The soak keeps to one glibc arena (M_ARENA_MAX), as malloc_trim does not hand back the freed
//    top of the other threads' arenas.
//    After a warm-up (the first third of the run, at least 5 s) every sample must stay within
//    kRssAllowance of the warm-up's largest. The largest project scene's world is about 10 MiB,
//    so the allowance covers opening it for the first time after the warm-up, and a leak of a
//    few hundred bytes per command over a run of minutes breaks it.
// 2. The heap in use (glibc's mallinfo2: bytes handed out and not freed) compared with the
//    first time that same scene was opened. It may differ by the soak's own small bookkeeping
//    and by the chunks glibc's per-thread cache holds (it counts them as in use; up to about
//    250 KiB), hence kHeapAllowance. This catches a leak of tens of bytes per step.
//
// Besides, the RSS is sampled every kRssSampleSeconds whatever the state, for the peak the
// summary reports (that peak includes legitimate working sets, such as four overlay runs of the
// largest scene at dt = 1 s, whose broad phase pairs every box with every other).
//
// Under AddressSanitizer both rules are off: its quarantine holds freed memory on purpose and
// its allocator does not report to mallinfo2; LeakSanitizer checks for leaks at exit instead.
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace soak {

inline constexpr std::size_t kMiB = 1024 * 1024;
inline constexpr std::size_t kRssAllowance = 32 * kMiB;
inline constexpr std::size_t kHeapAllowance = 1 * kMiB;
inline constexpr double kRssSampleSeconds = 2.0;

/// Resident set size of this process. unit: bytes; 0 if /proc is unreadable
std::size_t residentBytes();
/// Bytes allocated with malloc and not freed, or nothing where no allocator reports it.
std::optional<std::size_t> heapInUse();

class MemoryWatch {
 public:
  /// `runSeconds`: how long the whole run is meant to take (the warm-up is a third of it).
  explicit MemoryWatch(double runSeconds);

  bool enabled() const { return enabled_; }
  /// Every few seconds, whatever the state: for the peak only.
  void sample(double elapsedSeconds);
  /// Right after `scene` (a project scene) was opened afresh: both rules. "" or what broke.
  std::string afterFreshOpen(const std::string& scene, double elapsedSeconds);

  std::size_t peakRss() const { return peakRss_; }
  /// The rule's samples: the warm-up's largest, and the largest since.
  std::size_t warmUpRss() const { return warmUpRss_; }
  std::size_t laterRss() const { return laterRss_; }
  std::size_t rssComparisons() const { return rssComparisons_; }
  /// Largest growth of the heap in use over a scene's first open, and over how many reopenings.
  std::ptrdiff_t largestHeapGrowth() const { return largestGrowth_; }
  std::size_t heapComparisons() const { return heapComparisons_; }
  const std::vector<std::size_t>& samples() const { return samples_; }

 private:
  std::string checkRss(const std::string& scene, double elapsedSeconds);
  std::string checkHeap(const std::string& scene);

  bool enabled_ = true;
  double warmUpSeconds_;
  double lastSample_ = -1e300;
  double lastTrimmedSample_ = -1e300;
  std::size_t warmUpRss_ = 0;
  std::size_t laterRss_ = 0;
  std::size_t rssComparisons_ = 0;
  std::size_t peakRss_ = 0;
  std::vector<std::size_t> samples_;
  std::map<std::string, std::size_t> firstHeap_;
  std::ptrdiff_t largestGrowth_ = 0;
  std::size_t heapComparisons_ = 0;
};

}  // namespace soak
