#pragma once

#include <string>
#include <vector>

namespace colmap_gcn {

// Splits on any of the delimiter characters, keeping empty fields.
std::vector<std::string> StringSplit(const std::string& str,
                                     const std::string& delimiters);

std::string StringTrim(const std::string& str);

// The items of an option's comma list, trimmed, empty items dropped.
std::vector<std::string> SplitCommaList(const std::string& list);

// The integers of a comma list; throws Error naming `what` on anything else.
std::vector<int> ParseIntList(const std::string& list, const std::string& what);

bool StringStartsWith(const std::string& str, const std::string& prefix);

// Joins elements with a separator.
std::string StringJoin(const std::vector<std::string>& parts,
                       const std::string& separator);

// Quotes an argument for a POSIX shell, for logging commands users can copy.
std::string ShellQuote(const std::string& str);

}  // namespace colmap_gcn
