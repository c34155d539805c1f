#pragma once
// FNV-1a, 64 bit (Fowler, Noll and Vo): the state hash's (World::stateHash) and the recording
// files' checksum. Not a cryptographic hash: it tells states and files apart, and catches damage.
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace phys {

class Fnv1a {
 public:
  void bytes(const void* data, std::size_t size) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
      hash_ ^= b[i];
      hash_ *= 1099511628211ull;
    }
  }
  /// The bytes of a value with no padding in it (a number, a vector of doubles, an enum).
  template <typename T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes(&v, sizeof(v));
  }
  std::uint64_t hash() const { return hash_; }

 private:
  std::uint64_t hash_ = 14695981039346656037ull;
};

}  // namespace phys
