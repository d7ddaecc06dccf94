#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace colmap_gcn {

// Every user-facing failure (bad input, failing COLMAP, corrupt files) is an
// Error whose what() is one line; the front end prints it and exits non-zero.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

namespace internal {
inline void StreamAll(std::ostringstream&) {}
template <typename T, typename... Rest>
void StreamAll(std::ostringstream& stream,
               const T& value,
               const Rest&... rest) {
  stream << value;
  StreamAll(stream, rest...);
}
}  // namespace internal

// ThrowError("cannot open ", path) concatenates its arguments like a stream.
template <typename... Args>
[[noreturn]] void ThrowError(const Args&... args) {
  std::ostringstream stream;
  internal::StreamAll(stream, args...);
  throw Error(stream.str());
}

// Internal invariants (programming errors, not user errors).
#define THROW_CHECK(condition)                                      \
  do {                                                              \
    if (!(condition)) {                                             \
      ::colmap_gcn::ThrowError(                                     \
          __FILE__, ":", __LINE__, ": check failed: ", #condition); \
    }                                                               \
  } while (false)

}  // namespace colmap_gcn
