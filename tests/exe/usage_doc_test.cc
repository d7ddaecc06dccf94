// docs/usage.md against `colmap <command> -h`: every command of ours has a
// section, every option it prints has a row with the same default, and
// every row is an option the command has.

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "exe/colmap.h"
#include "frontend_command.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

// Option name -> its default as `-h` prints it ("(=x)" without the
// brackets), or kNoDefault.
typedef std::map<std::string, std::string> OptionDefaults;
const char kNoDefault[] = "\x01none";

OptionDefaults HelpOptions(const std::string& help) {
  static const std::regex kOption(
      R"(^  --(\S+)(?: arg(?: \(=(.*?)\)(?=\s|$))?)?)");
  OptionDefaults options;
  for (const std::string& line : StringSplit(help, "\n")) {
    std::smatch match;
    if (!std::regex_search(line, match, kOption)) continue;
    options[match[1].str()] = match[2].matched ? match[2].str() : kNoDefault;
  }
  return options;
}

// Section "## `colmap <command>`" -> its rows "| `--name` | default | ...":
// a default in backticks is the default; anything else means none.
std::map<std::string, OptionDefaults> UsageDoc(const std::string& text) {
  static const std::regex kSection(R"(^## `colmap (\S+)`)");
  static const std::regex kRow(R"(^\| `--([^`]+)` \| ([^|]*)\|)");
  std::map<std::string, OptionDefaults> doc;
  OptionDefaults* section = nullptr;
  for (const std::string& line : StringSplit(text, "\n")) {
    std::smatch match;
    if (std::regex_search(line, match, kSection)) {
      section = &doc[match[1].str()];
    } else if (section != nullptr && std::regex_search(line, match, kRow)) {
      const std::string cell = StringTrim(match[2].str());
      const bool quoted =
          cell.size() >= 2 && cell.front() == '`' && cell.back() == '`';
      (*section)[match[1].str()] =
          quoted ? cell.substr(1, cell.size() - 2) : kNoDefault;
    }
  }
  return doc;
}

std::string Row(const std::string& name, const std::string& value) {
  return "| `--" + name + "` | " +
         (value == kNoDefault ? "required" : "`" + value + "`") + " | |";
}

TEST(UsageDoc, MatchesEveryCommandsHelp) {
  const auto doc =
      UsageDoc(ReadTextFile(JoinPaths(COLMAP_GCN_SOURCE_DIR, "docs/usage.md")));
  const std::vector<std::string> commands = GcnCommandNames();
  for (const std::string& command : commands) {
    const test::CommandResult result = test::RunColmap(command + " -h");
    ASSERT_EQ(result.exit_code, 0) << command << ": " << result.err;
    const OptionDefaults help = HelpOptions(result.out);
    ASSERT_GT(help.size(), 1u) << command;
    const auto section = doc.find(command);
    if (section == doc.end()) {
      ADD_FAILURE() << "docs/usage.md has no section ## `colmap " << command
                    << "`";
      continue;
    }
    for (const auto& [name, value] : help) {
      const auto row = section->second.find(name);
      if (row == section->second.end()) {
        ADD_FAILURE() << "docs/usage.md, colmap " << command << ": missing row "
                      << Row(name, value);
      } else {
        EXPECT_EQ(row->second, value)
            << "docs/usage.md, colmap " << command << " --" << name
            << ": default differs from -h; -h says " << Row(name, value);
      }
    }
    for (const auto& [name, value] : section->second) {
      EXPECT_EQ(help.count(name), 1u)
          << "docs/usage.md, colmap " << command << ": --" << name
          << " is not an option of the command";
    }
  }
  for (const auto& [command, options] : doc) {
    EXPECT_NE(std::find(commands.begin(), commands.end(), command),
              commands.end())
        << "docs/usage.md documents colmap " << command
        << ", which is not a command of ours";
  }
}

}  // namespace
}  // namespace colmap_gcn
