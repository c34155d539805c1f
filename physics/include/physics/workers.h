#pragma once
// The threads a world's step may use (SolverSettings::threads), through oneTBB: a task arena of
// that many threads, and runs of a stage's independent pieces on it. Each piece is a fixed range
// of lane groups, bodies or particles that shares nothing with the others, so the result is the
// same bit for bit whatever the number of threads (docs/physics.md, "Threads").
#include <cstddef>
#include <memory>

namespace phys {

/// f(begin, end) called through a pointer, without std::function's allocation: the callable
/// stays where the caller made it, which outlives the call.
class RangeFunction {
 public:
  template <class F>
  RangeFunction(F& f)  // NOLINT(google-explicit-constructor): made where a range function is passed
      : object_(&f), call_([](void* o, std::size_t b, std::size_t e) { (*static_cast<F*>(o))(b, e); }) {}
  void operator()(std::size_t begin, std::size_t end) const { call_(object_, begin, end); }

 private:
  void* object_;
  void (*call_)(void*, std::size_t, std::size_t);
};

class Workers {
 public:
  Workers();
  ~Workers();
  /// A copy has an arena of its own with as many threads.
  Workers(const Workers& other);
  Workers& operator=(const Workers& other);
  Workers(Workers&& other) noexcept;
  Workers& operator=(Workers&& other) noexcept;

  /// 1 runs everything on the calling thread; more makes an arena of that many (the caller's
  /// included) when the number changes.
  void setThreads(int threads);
  int threads() const { return threads_; }
  /// Sets up the threads' arena if it is not yet: World::step calls it first, so that the arena's
  /// first use, which may come in a stage long after the world was made (the contact bins' first
  /// deal), does not allocate, and a copy that never steps (a rewind's keyframe) sets up none.
  void prepare() const;
  /// f(begin, end) over ranges that cover [0, count), none longer than `grain`: on the arena's
  /// threads, or once over all of it on the calling thread with one thread or count <= grain.
  /// The ranges must share nothing: they run in any order, at once.
  void forEach(std::size_t count, std::size_t grain, RangeFunction f) const;

 private:
  struct Arena;
  std::unique_ptr<Arena> arena_;
  int threads_ = 1;
};

/// workers->forEach(count, grain, f), or f(0, count) on the calling thread when `workers` is null
/// (a world on one thread hands its stages none).
void forEachRange(const Workers* workers, std::size_t count, std::size_t grain, RangeFunction f);

}  // namespace phys
