#pragma once

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <type_traits>
#include <utility>

namespace colmap_gcn {

// The byte writer and reader of the project's binary files (model file,
// CNN model and cache bytes, COLMAP's binary models). Values are copied as
// they are in memory: little-endian PODs without padding, the only hosts we
// target.
class ByteWriter {
 public:
  template <typename T>
  void Put(const T& value) {
    static_assert(std::is_trivially_copyable<T>::value, "POD only");
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  void PutFloats(const float* data, size_t count) {
    bytes_.append(reinterpret_cast<const char*>(data), count * sizeof(float));
  }
  // u64 length + bytes.
  void PutString(const std::string& value) {
    Put<uint64_t>(value.size());
    bytes_ += value;
  }
  std::string& Bytes() { return bytes_; }

 private:
  std::string bytes_;
};

// Reads bytes[begin, end) front to back. Running out of bytes calls
// `fail(position)`, which must throw the format's own message (it names the
// file); the reader never reads past `end`.
class ByteReader {
 public:
  using Failure = std::function<void(size_t position)>;

  ByteReader(const std::string& bytes, size_t begin, size_t end, Failure fail)
      : bytes_(bytes), pos_(begin), end_(end), fail_(std::move(fail)) {}

  template <typename T>
  T Get() {
    static_assert(std::is_trivially_copyable<T>::value, "POD only");
    Need(sizeof(T));
    T value;
    std::memcpy(&value, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }
  void GetFloats(float* data, size_t count) {
    if (count > Remaining() / sizeof(float)) Fail();
    std::memcpy(data, bytes_.data() + pos_, count * sizeof(float));
    pos_ += count * sizeof(float);
  }
  // u64 length + bytes.
  std::string GetString() {
    const uint64_t size = Get<uint64_t>();
    Need(size);
    std::string value = bytes_.substr(pos_, size);
    pos_ += size;
    return value;
  }
  // A NUL-terminated string (COLMAP's image names).
  std::string GetCString() {
    const size_t nul = bytes_.find('\0', pos_);
    if (nul == std::string::npos || nul >= end_) Fail();
    std::string value = bytes_.substr(pos_, nul - pos_);
    pos_ = nul + 1;
    return value;
  }

  size_t Position() const { return pos_; }
  size_t Remaining() const { return end_ - pos_; }

  // Calls fail(Position()).
  [[noreturn]] void Fail() const {
    fail_(pos_);
    std::abort();  // fail must throw
  }

 private:
  void Need(uint64_t size) const {
    if (size > Remaining()) Fail();
  }

  const std::string& bytes_;
  size_t pos_;
  size_t end_;
  Failure fail_;
};

}  // namespace colmap_gcn
