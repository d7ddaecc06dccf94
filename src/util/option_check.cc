#include "util/option_check.h"

#include <algorithm>

#include "util/string.h"

namespace colmap_gcn {

OptionError::OptionError(const void* field,
                         const std::string& name,
                         const std::string& requirement,
                         const std::string& value)
    : Error(name + " must " + requirement + " (got " + value + ")"),
      field_(field),
      name_(name),
      requirement_(requirement),
      value_(value) {}

std::string OptionError::MessageFor(const std::string& name) const {
  return name + " must " + requirement_ + " (got " + value_ + ")";
}

namespace internal {

std::string FormatOptionValue(const std::string& value) {
  return "\"" + value + "\"";
}

std::string FormatOptionValue(const char* value) {
  return FormatOptionValue(std::string(value));
}

std::string FormatOptionValue(bool value) { return value ? "1" : "0"; }

void ThrowOptionError(const void* field,
                      const char* name,
                      const std::string& requirement,
                      const std::string& value) {
  throw OptionError(field, name, requirement, value);
}

bool IsOneOf(const std::string& value,
             const std::vector<std::string>& choices) {
  return std::find(choices.begin(), choices.end(), value) != choices.end();
}

std::string JoinChoices(const std::vector<std::string>& choices) {
  return StringJoin(choices, "|");
}

}  // namespace internal
}  // namespace colmap_gcn
