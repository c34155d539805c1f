#include "physics/workers.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

namespace phys {

struct Workers::Arena {
  // No more threads than the machine runs at once (oneTBB's default concurrency, which follows the
  // process's affinity mask): oneTBB would run no more anyway, and warned on stderr that it had not.
  // The pieces a stage is cut into follow the threads asked for, so the state does not change.
  explicit Arena(int threads) : arena(std::min(threads, tbb::info::default_concurrency())) {}
  tbb::task_arena arena;
};

Workers::Workers() = default;
Workers::~Workers() = default;
Workers::Workers(Workers&& other) noexcept = default;
Workers& Workers::operator=(Workers&& other) noexcept = default;

Workers::Workers(const Workers& other) {
  setThreads(other.threads_);
}

Workers& Workers::operator=(const Workers& other) {
  if (this != &other) setThreads(other.threads_);
  return *this;
}

void Workers::setThreads(int threads) {
  if (threads == threads_ && (threads <= 1 || arena_)) return;
  threads_ = threads;
  arena_.reset();
  if (threads > 1) arena_ = std::make_unique<Arena>(threads);
}

void Workers::prepare() const {
  if (arena_ && !arena_->arena.is_active()) arena_->arena.initialize();
}

void Workers::forEach(std::size_t count, std::size_t grain, RangeFunction f) const {
  if (count == 0) return;
  if (!arena_ || count <= grain) {
    f(0, count);
    return;
  }
  // The simple partitioner halves the range until each piece is at most `grain`: where it cuts
  // depends on count and grain alone, and each piece's work is its own, so the result does not
  // depend on which thread runs what.
  arena_->arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, count, grain),
        [&](const tbb::blocked_range<std::size_t>& r) { f(r.begin(), r.end()); }, tbb::simple_partitioner());
  });
}

void forEachRange(const Workers* workers, std::size_t count, std::size_t grain, RangeFunction f) {
  if (workers == nullptr)
    f(0, count);
  else
    workers->forEach(count, grain, f);
}

}  // namespace phys
