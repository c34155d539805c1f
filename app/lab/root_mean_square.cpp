#include "root_mean_square.h"

#include <cmath>

namespace lab {

void RootMeanSquare::add(double x, double weight) {
  weights_ += weight;
  if (!std::isfinite(x)) {
    unfinite_ += x * x;
    return;
  }
  if (x == 0.0) return;
  int exponent = 0;
  std::frexp(x, &exponent);  // |x| = m 2^exponent with 0.5 <= m < 1
  // The first sample that counts sets the scale; a larger one rescales what came before to it.
  if (scaledSquares_ == 0.0 || exponent > exponent_) {
    scaledSquares_ = std::ldexp(scaledSquares_, 2 * (exponent_ - exponent));
    exponent_ = exponent;
  }
  const double scaled = std::ldexp(x, -exponent_);
  scaledSquares_ += scaled * scaled * weight;
}

double RootMeanSquare::value() const {
  if (!std::isfinite(unfinite_)) return unfinite_;
  if (weights_ <= 0.0) return 0.0;
  return std::ldexp(std::sqrt(scaledSquares_ / weights_), exponent_);
}

}  // namespace lab
