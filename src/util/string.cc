#include "util/string.h"

#include <algorithm>

#include "util/error.h"

namespace colmap_gcn {

std::vector<std::string> StringSplit(const std::string& str,
                                     const std::string& delimiters) {
  std::vector<std::string> parts;
  size_t begin = 0;
  while (true) {
    const size_t end = str.find_first_of(delimiters, begin);
    if (end == std::string::npos) {
      parts.push_back(str.substr(begin));
      break;
    }
    parts.push_back(str.substr(begin, end - begin));
    begin = end + 1;
  }
  return parts;
}

std::string StringTrim(const std::string& str) {
  const char* kWhitespace = " \t\r\n\f\v";
  const size_t begin = str.find_first_not_of(kWhitespace);
  if (begin == std::string::npos) {
    return "";
  }
  const size_t end = str.find_last_not_of(kWhitespace);
  return str.substr(begin, end - begin + 1);
}

std::vector<std::string> SplitCommaList(const std::string& list) {
  std::vector<std::string> items;
  for (const std::string& item : StringSplit(list, ",")) {
    const std::string trimmed = StringTrim(item);
    if (!trimmed.empty()) items.push_back(trimmed);
  }
  return items;
}

std::vector<int> ParseIntList(const std::string& list,
                              const std::string& what) {
  std::vector<int> values;
  for (const std::string& item : SplitCommaList(list)) {
    size_t end = 0;
    int value = 0;
    try {
      value = std::stoi(item, &end);
    } catch (const std::exception&) {
      end = 0;
    }
    if (end != item.size()) {
      ThrowError(what, ": \"", item, "\" is not an integer");
    }
    values.push_back(value);
  }
  return values;
}

bool StringStartsWith(const std::string& str, const std::string& prefix) {
  return str.size() >= prefix.size() &&
         str.compare(0, prefix.size(), prefix) == 0;
}

std::string StringJoin(const std::vector<std::string>& parts,
                       const std::string& separator) {
  std::string joined;
  for (size_t i = 0; i < parts.size(); ++i) {
    if (i > 0) {
      joined += separator;
    }
    joined += parts[i];
  }
  return joined;
}

std::string ShellQuote(const std::string& str) {
  const bool safe =
      !str.empty() && std::all_of(str.begin(), str.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) ||
               std::string("_-./=:,+@%").find(c) != std::string::npos;
      });
  if (safe) {
    return str;
  }
  std::string quoted = "'";
  for (const char c : str) {
    if (c == '\'') {
      quoted += "'\\''";
    } else {
      quoted += c;
    }
  }
  return quoted + "'";
}

}  // namespace colmap_gcn
