#pragma once
// The root mean square of samples taken one at a time: the lab's RMS figures over a run (the
// tracking error over the steps and over the parts, each drive's torque and force).
#include <cmath>

namespace lab {

/// sqrt(sum of w x^2 / sum of w) over the samples added so far.
class RootMeanSquare {
 public:
  /// One sample, counted `weight` times (a character's error once for each of its parts).
  void add(double x, double weight = 1.0) {
    sumOfSquares_ += x * x * weight;
    weights_ += weight;
  }
  /// 0 before any sample.
  double value() const { return weights_ > 0.0 ? std::sqrt(sumOfSquares_ / weights_) : 0.0; }

 private:
  double sumOfSquares_ = 0.0;
  double weights_ = 0.0;
};

}  // namespace lab
