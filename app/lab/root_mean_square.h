#pragma once
// The root mean square of samples taken one at a time: the lab's RMS figures over a run (the
// tracking error over the steps and over the parts, each drive's torque and force).
namespace lab {

/// sqrt(sum of w x^2 / sum of w) over the samples added so far, finite for any finite samples:
/// squared as they come, samples beyond 1e154 would overflow to infinity and read "blew up".
class RootMeanSquare {
 public:
  /// One sample, counted `weight` times (a character's error once for each of its parts).
  void add(double x, double weight = 1.0);
  /// 0 before any sample; infinite once a sample was, NaN once one was NaN (as a plain sum of
  /// squares would be), whatever came after.
  double value() const;

 private:
  // The samples are kept divided by 2^exponent_, the power of two just above the largest so far
  // (as hypot scales), so their squares stay near 1. Dividing by a power of two is exact, so
  // ordinary samples give the plain formula's result to the bit.
  int exponent_ = 0;
  double scaledSquares_ = 0.0;  // sum of w (x / 2^exponent_)^2
  double weights_ = 0.0;
  double unfinite_ = 0.0;  // sum of the squares of the samples that were not finite: 0, inf or NaN
};

}  // namespace lab
