#include "history.h"

#include <algorithm>

namespace sandbox {

void History::add(float value, double seconds) {
  owed_ += seconds;
  int n = 0;
  while (owed_ >= kSampleSeconds && n < kSamples) {
    values_[static_cast<std::size_t>(next_)] = value;
    next_ = (next_ + 1) % kSamples;
    filled_ = std::min(filled_ + 1, kSamples);
    owed_ -= kSampleSeconds;
    ++n;
  }
  if (n == kSamples) owed_ = 0.0;  // a long stall: the ring is full of this value already
}

void History::clear() {
  std::fill(values_.begin(), values_.end(), 0.0f);
  next_ = filled_ = 0;
  owed_ = 0.0;
}

float History::max() const {
  return filled_ == 0 ? 0.0f : *std::max_element(values_.begin(), values_.end());
}

float History::last() const {
  return filled_ == 0 ? 0.0f : values_[static_cast<std::size_t>((next_ + kSamples - 1) % kSamples)];
}

}  // namespace sandbox
