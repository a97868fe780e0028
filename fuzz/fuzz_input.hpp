#pragma once
// Reads typed values from a libFuzzer input: bytes are consumed front to back; past the end
// every value reads as zero, so every input decodes.

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace tumble_fuzz {

class Input {
 public:
  Input(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  std::uint8_t byte() {
    if (pos_ >= size_) return 0;
    return data_[pos_++];
  }

  /// A double: a byte selects the encoding, so that the fuzzer reaches both ordinary values
  /// (a 32-bit integer / 2^16, |x| < 32768) and every bit pattern (NaN, inf, subnormals, 1e308).
  double real() {
    const std::uint8_t kind = byte();
    if (kind & 1u) {
      std::uint64_t bits = 0;
      for (int i = 0; i < 8; ++i) bits = (bits << 8) | byte();
      double x;
      std::memcpy(&x, &bits, sizeof x);
      return x;
    }
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v = (v << 8) | byte();
    return static_cast<double>(static_cast<std::int32_t>(v)) / 65536.0;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

}  // namespace tumble_fuzz
