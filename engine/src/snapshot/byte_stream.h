// Little-endian byte streams for snapshots: a writer that appends, and a reader that checks
// every read against the end of its buffer, so a truncated or corrupt snapshot is an error, never
// a read out of bounds. Internal to the engine.
#pragma once

#include <bit>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/math.h"

namespace engine::detail {

class ByteWriter {
 public:
  explicit ByteWriter(std::vector<std::uint8_t>* out) : out_(out) {}
  void U8(std::uint8_t v) { out_->push_back(v); }
  void U32(std::uint32_t v) { Bytes(v, 4); }
  void U64(std::uint64_t v) { Bytes(v, 8); }
  void I64(std::int64_t v) { Bytes(static_cast<std::uint64_t>(v), 8); }
  void F64(double v) { Bytes(std::bit_cast<std::uint64_t>(v), 8); }

 private:
  void Bytes(std::uint64_t v, int count) {
    for (int i = 0; i < count; ++i) out_->push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  std::vector<std::uint8_t>* out_;
};

/// Reads until the first failure; after it every read gives 0 and Ok() is false.
class ByteReader {
 public:
  explicit ByteReader(std::span<const std::uint8_t> in) : in_(in) {}
  std::uint8_t U8() { return static_cast<std::uint8_t>(Bytes(1)); }
  std::uint32_t U32() { return static_cast<std::uint32_t>(Bytes(4)); }
  std::uint64_t U64() { return Bytes(8); }
  std::int64_t I64() { return static_cast<std::int64_t>(Bytes(8)); }
  double F64() { return std::bit_cast<double>(Bytes(8)); }
  /// A count of items each at least `min_bytes` long: more than the rest of the buffer could
  /// hold fails at once, so a corrupt count never asks for a huge allocation.
  std::uint32_t Count(std::size_t min_bytes) {
    const std::uint32_t n = U32();
    if (static_cast<std::uint64_t>(n) * min_bytes > Remaining()) Fail();
    return ok_ ? n : 0;
  }
  /// Marks the stream bad (a value read was out of its range).
  void Fail() { ok_ = false; }
  bool Check(bool condition) {
    if (!condition) ok_ = false;
    return ok_;
  }
  bool Ok() const { return ok_; }
  std::size_t Position() const { return at_; }
  std::size_t Remaining() const { return in_.size() - at_; }

 private:
  std::uint64_t Bytes(int count) {
    if (!ok_ || Remaining() < static_cast<std::size_t>(count)) {
      ok_ = false;
      return 0;
    }
    std::uint64_t v = 0;
    for (int i = 0; i < count; ++i) v |= static_cast<std::uint64_t>(in_[at_ + i]) << (8 * i);
    at_ += static_cast<std::size_t>(count);
    return v;
  }
  std::span<const std::uint8_t> in_;
  std::size_t at_ = 0;
  bool ok_ = true;
};

inline void WriteVec(ByteWriter& out, Vec2 v) {
  out.F64(v.x);
  out.F64(v.y);
}

inline Vec2 ReadVec(ByteReader& in) {
  const double x = in.F64();
  return {x, in.F64()};
}

}  // namespace engine::detail
