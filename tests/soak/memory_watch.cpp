#include "memory_watch.h"

#include <algorithm>
#include <cstdio>
#include <fstream>

#include <malloc.h>
#include <unistd.h>

#if defined(__SANITIZE_ADDRESS__)
#define SOAK_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SOAK_UNDER_ASAN 1
#endif
#endif

namespace soak {
namespace {

std::string mib(std::size_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / kMiB);
  return text;
}

}  // namespace

std::size_t residentBytes() {
  std::ifstream statm("/proc/self/statm");
  std::size_t size = 0, resident = 0;
  if (!(statm >> size >> resident)) return 0;
  return resident * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

std::optional<std::size_t> heapInUse() {
#if defined(SOAK_UNDER_ASAN)
  return std::nullopt;
#elif defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
  const struct mallinfo2 info = mallinfo2();
  return info.uordblks + info.hblkhd;  // small chunks in use, and blocks mapped on their own
#else
  return std::nullopt;
#endif
}

MemoryWatch::MemoryWatch(double runSeconds) : warmUpSeconds_(std::max(5.0, runSeconds / 3.0)) {
#if defined(SOAK_UNDER_ASAN)
  enabled_ = false;
#elif defined(__GLIBC__)
  // One arena for every thread. Each thread that allocates (the background steps, a recording's
  // save, oneTBB's workers) otherwise gets an arena of its own, whose freed top malloc_trim does
  // not hand back: the trimmed resident set then crept from 30 to 78 MiB over 400 s of seed 11
  // with the heap in use flat, and broke the rule below with nothing leaked. With one arena it
  // stayed at 13 to 25 MiB for 300 s.
  mallopt(M_ARENA_MAX, 1);
#endif
}

void MemoryWatch::sample(double elapsedSeconds) {
  if (elapsedSeconds - lastSample_ < kRssSampleSeconds) return;
  lastSample_ = elapsedSeconds;
  const std::size_t rss = residentBytes();
  samples_.push_back(rss);
  peakRss_ = std::max(peakRss_, rss);
}

std::string MemoryWatch::afterFreshOpen(const std::string& scene, double elapsedSeconds) {
  if (!enabled_) return {};
  if (std::string why = checkHeap(scene); !why.empty()) return why;
  return checkRss(scene, elapsedSeconds);
}

std::string MemoryWatch::checkRss(const std::string& scene, double elapsedSeconds) {
  if (elapsedSeconds - lastTrimmedSample_ < kRssSampleSeconds) return {};
  lastTrimmedSample_ = elapsedSeconds;
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
  const std::size_t rss = residentBytes();
  peakRss_ = std::max(peakRss_, rss);
  if (rss == 0) return {};
  if (elapsedSeconds < warmUpSeconds_) {
    warmUpRss_ = std::max(warmUpRss_, rss);
    return {};
  }
  ++rssComparisons_;
  laterRss_ = std::max(laterRss_, rss);
  if (rss > warmUpRss_ + kRssAllowance) {
    return "memory: right after opening " + scene + " afresh at " +
           std::to_string(static_cast<int>(elapsedSeconds)) + " s, the resident set is " + mib(rss) +
           ", more than " + mib(kRssAllowance) + " above the warm-up's largest, " + mib(warmUpRss_);
  }
  return {};
}

std::string MemoryWatch::checkHeap(const std::string& scene) {
  const std::optional<std::size_t> heap = heapInUse();
  if (!heap) return {};
  const auto [first, inserted] = firstHeap_.emplace(scene, *heap);
  if (inserted) return {};
  ++heapComparisons_;
  const std::ptrdiff_t growth =
      static_cast<std::ptrdiff_t>(*heap) - static_cast<std::ptrdiff_t>(first->second);
  largestGrowth_ = std::max(largestGrowth_, growth);
  if (growth > static_cast<std::ptrdiff_t>(kHeapAllowance)) {
    return "memory: " + std::to_string(*heap) + " bytes of heap in use right after opening " + scene +
           " afresh, " + std::to_string(growth) +
           " more than the first time it was opened (allowed: " + std::to_string(kHeapAllowance) + ")";
  }
  return {};
}

}  // namespace soak
