#pragma once
// The real-time factor: simulated seconds per wall second over the last second of frames, which the
// Stats panel shows (red when the physics cannot keep up with the time scale asked for).
#include <array>
#include <cstddef>
#include <optional>

namespace sandbox {

class RealTimeMeter {
 public:
  /// One frame: `simulated` seconds of the world's clock advanced in `wall` seconds. A paused
  /// frame is left out (`running` false): a paused world is not slow.
  void add(double simulated, double wall, bool running);
  /// Simulated seconds per wall second over the running frames of the last second or so; none
  /// before the first running frame, or after a pause until frames run again.
  std::optional<double> factor() const;
  /// True when the factor is under `timeScale` by more than a twentieth: the steps a frame needs
  /// take longer than the frame (or the cap on steps a frame drops the backlog).
  bool fallingBehind(double timeScale) const;

 private:
  static constexpr std::size_t kFrames = 120;  // two seconds at 60 frames a second, at most
  static constexpr double kWindow = 1.0;       // unit: s of wall time summed
  std::array<double, kFrames> simulated_{}, wall_{};
  std::size_t next_ = 0, count_ = 0;
};

}  // namespace sandbox
