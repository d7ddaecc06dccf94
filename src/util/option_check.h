#pragma once

#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "util/error.h"

namespace colmap_gcn {

// A rejected option value. what() reads "<field> must <requirement> (got
// <value>)", e.g. "k1 must be >= 1 (got 0)". Field() is the address of the
// checked member: OptionManager::Check uses it to name the command-line flag
// bound to that member ("--GcnMatching.k1 must be >= 1 (got 0)").
class OptionError : public Error {
 public:
  OptionError(const void* field,
              const std::string& name,
              const std::string& requirement,
              const std::string& value);

  const void* Field() const { return field_; }
  const std::string& Name() const { return name_; }
  const std::string& Requirement() const { return requirement_; }
  const std::string& Value() const { return value_; }

  // The message with `name` (e.g. "--GcnMatching.k1") for the field.
  std::string MessageFor(const std::string& name) const;

 private:
  const void* field_;
  std::string name_;
  std::string requirement_;
  std::string value_;
};

namespace internal {

// Values as users typed them: numbers as streamed, strings quoted.
template <typename T>
std::string FormatOptionValue(const T& value) {
  std::ostringstream stream;
  stream << value;
  return stream.str();
}
std::string FormatOptionValue(const std::string& value);
std::string FormatOptionValue(const char* value);
std::string FormatOptionValue(bool value);
template <typename T>
std::string FormatOptionValue(const std::vector<T>& values) {
  std::string text;
  for (size_t i = 0; i < values.size(); ++i) {
    text += (i > 0 ? "," : "") + FormatOptionValue(values[i]);
  }
  return text;
}

[[noreturn]] void ThrowOptionError(const void* field,
                                   const char* name,
                                   const std::string& requirement,
                                   const std::string& value);

// "[0, 1]", "(0, 1]", ...
template <typename T>
std::string FormatInterval(const T& low,
                           bool low_closed,
                           const T& high,
                           bool high_closed) {
  return std::string(low_closed ? "[" : "(") + FormatOptionValue(low) + ", " +
         FormatOptionValue(high) + (high_closed ? "]" : ")");
}

template <typename T, typename B>
bool InInterval(const T& value,
                const B& low,
                bool low_closed,
                const B& high,
                bool high_closed) {
  // Written so that NaN fails every bound.
  const bool above = low_closed ? value >= low : value > low;
  const bool below = high_closed ? value <= high : value < high;
  return above && below;
}

bool IsOneOf(const std::string& value, const std::vector<std::string>& choices);
std::string JoinChoices(const std::vector<std::string>& choices);

}  // namespace internal

// The names users type for the values of an enum option, in the order help
// and errors list them: {{"sgd", GcnOptimizer::kSgd}, {"adam", ...}}.
template <typename Enum>
using EnumNames = std::vector<std::pair<std::string, Enum>>;

// The name of `value` in `names` ("" when it has none).
template <typename Enum>
std::string EnumName(const EnumNames<Enum>& names, Enum value) {
  for (const auto& [name, entry] : names) {
    if (entry == value) return name;
  }
  return "";
}

// "a|b|c": the allowed names.
template <typename Enum>
std::string EnumChoices(const EnumNames<Enum>& names) {
  std::string text;
  for (const auto& entry : names) {
    text += (text.empty() ? "" : "|") + entry.first;
  }
  return text;
}

// The value named `text`; throws Error "<what> must be one of a|b (got
// "text")", `what` being the flag (e.g. "--GcnTraining.optimizer").
template <typename Enum>
Enum ParseEnum(const EnumNames<Enum>& names,
               const std::string& text,
               const std::string& what) {
  for (const auto& [name, value] : names) {
    if (name == text) return value;
  }
  ThrowError(what,
             " must be one of ",
             EnumChoices(names),
             " (got ",
             internal::FormatOptionValue(text),
             ")");
}

// Option checks for Options::Check(), in the manner of COLMAP's
// CHECK_OPTION_*: each throws OptionError naming the member (as written in
// the macro call), the requirement and the offending value. `field` must be
// an lvalue member so its address can be matched to a flag.

// Generic: CHECK_OPTION(path, !path.empty(), "name a file").
#define CHECK_OPTION(field, condition, requirement)          \
  do {                                                       \
    if (!(condition)) {                                      \
      ::colmap_gcn::internal::ThrowOptionError(              \
          &(field),                                          \
          #field,                                            \
          (requirement),                                     \
          ::colmap_gcn::internal::FormatOptionValue(field)); \
    }                                                        \
  } while (false)

#define CHECK_OPTION_GE(field, bound) \
  CHECK_OPTION(field,                 \
               (field) >= (bound),    \
               "be >= " + ::colmap_gcn::internal::FormatOptionValue(bound))
#define CHECK_OPTION_GT(field, bound) \
  CHECK_OPTION(field,                 \
               (field) > (bound),     \
               "be > " + ::colmap_gcn::internal::FormatOptionValue(bound))
#define CHECK_OPTION_LE(field, bound) \
  CHECK_OPTION(field,                 \
               (field) <= (bound),    \
               "be <= " + ::colmap_gcn::internal::FormatOptionValue(bound))
#define CHECK_OPTION_LT(field, bound) \
  CHECK_OPTION(field,                 \
               (field) < (bound),     \
               "be < " + ::colmap_gcn::internal::FormatOptionValue(bound))

// Intervals: CHECK_OPTION_INTERVAL(t, 0.0, true, 1.0, false) is [0, 1);
// CHECK_OPTION_RANGE is the closed interval.
#define CHECK_OPTION_INTERVAL(field, low, low_closed, high, high_closed) \
  CHECK_OPTION(field,                                                    \
               ::colmap_gcn::internal::InInterval(                       \
                   field, low, low_closed, high, high_closed),           \
               "be in " + ::colmap_gcn::internal::FormatInterval(        \
                              low, low_closed, high, high_closed))
#define CHECK_OPTION_RANGE(field, low, high) \
  CHECK_OPTION_INTERVAL(field, low, true, high, true)

// A closed choice: CHECK_OPTION_ONE_OF(optimizer, "sgd", "adam").
#define CHECK_OPTION_ONE_OF(field, ...)                            \
  CHECK_OPTION(field,                                              \
               ::colmap_gcn::internal::IsOneOf(                    \
                   field, std::vector<std::string>{__VA_ARGS__}),  \
               "be one of " + ::colmap_gcn::internal::JoinChoices( \
                                  std::vector<std::string>{__VA_ARGS__}))

// Options where one value stands for "not set" (e.g. -1: the model's
// value): exactly `unset`, or >= bound / in [low, high]. `meaning` explains
// the unset value in the message: "be -1 (the model's value) or >= 1".
#define CHECK_OPTION_UNSET_OR_GE(field, unset, meaning, bound)            \
  CHECK_OPTION(field,                                                     \
               (field) == (unset) || (field) >= (bound),                  \
               "be " + ::colmap_gcn::internal::FormatOptionValue(unset) + \
                   " (" + (meaning) + ") or >= " +                        \
                   ::colmap_gcn::internal::FormatOptionValue(bound))
#define CHECK_OPTION_UNSET_OR_RANGE(field, unset, meaning, low, high)       \
  CHECK_OPTION(                                                             \
      field,                                                                \
      (field) == (unset) ||                                                 \
          ::colmap_gcn::internal::InInterval(field, low, true, high, true), \
      "be " + ::colmap_gcn::internal::FormatOptionValue(unset) + " (" +     \
          (meaning) + ") or in " +                                          \
          ::colmap_gcn::internal::FormatInterval(low, true, high, true))

// Thread counts: -1 (all cores) or >= 1.
#define CHECK_OPTION_NUM_THREADS(field) \
  CHECK_OPTION_UNSET_OR_GE(field, -1, "all cores", 1)

}  // namespace colmap_gcn
