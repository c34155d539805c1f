#pragma once
// The last 10 seconds of a figure, for the Stats panel's plots: one sample per 1/60 s of wall
// time however fast frames come, in a ring that never allocates after construction.
#include <vector>

namespace sandbox {

class History {
 public:
  static constexpr double kSampleSeconds = 1.0 / 60.0;  ///< unit: s
  static constexpr int kSamples = 600;                  ///< 10 s

  History() : values_(kSamples, 0.0f) {}

  /// Records `value` as the figure over the last `seconds` of wall time: as many samples as
  /// that time covers (at most the whole ring).
  void add(float value, double seconds);
  void clear();

  /// The ring, and where its oldest sample is (ImGui::PlotLines's values_offset).
  const float* data() const { return values_.data(); }
  int offset() const { return next_; }
  int size() const { return kSamples; }
  /// Samples recorded so far, at most kSamples.
  int filled() const { return filled_; }
  /// Largest value in the ring (0 when empty), for the plot's scale.
  float max() const;
  /// The newest sample.
  float last() const;

 private:
  std::vector<float> values_;
  int next_ = 0;
  int filled_ = 0;
  double owed_ = 0.0;  // unit: s; wall time not yet turned into a sample
};

}  // namespace sandbox
