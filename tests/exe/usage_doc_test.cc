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

// Section "## `colmap <command>`" -> its rows "| `--name` | default | ...",
// plus the rows of the option groups ("## Options: <group>") it links to
// ("(#options-<group>)"): a default in backticks is the default; anything
// else means none.
std::map<std::string, OptionDefaults> UsageDoc(const std::string& text) {
  static const std::regex kCommand(R"(^## `colmap (\S+)`)");
  static const std::regex kGroup(R"(^## Options: (.+))");
  static const std::regex kRow(R"(^\| `--([^`]+)` \| ([^|]*)\|)");
  static const std::regex kLink(R"(\(#(options-[a-z0-9-]+)\))");
  std::map<std::string, OptionDefaults> commands;
  std::map<std::string, OptionDefaults> groups;
  std::map<std::string, std::vector<std::string>> links;
  OptionDefaults* section = nullptr;
  std::string command;
  for (const std::string& line : StringSplit(text, "\n")) {
    std::smatch match;
    if (std::regex_search(line, match, kCommand)) {
      command = match[1].str();
      section = &commands[command];
    } else if (std::regex_search(line, match, kGroup)) {
      command.clear();
      std::string anchor = "options-" + match[1].str();
      std::replace(anchor.begin(), anchor.end(), ' ', '-');
      section = &groups[anchor];
    } else if (section != nullptr && std::regex_search(line, match, kRow)) {
      const std::string cell = StringTrim(match[2].str());
      const bool quoted =
          cell.size() >= 2 && cell.front() == '`' && cell.back() == '`';
      (*section)[match[1].str()] =
          quoted ? cell.substr(1, cell.size() - 2) : kNoDefault;
    } else if (!command.empty()) {
      for (auto it = std::sregex_iterator(line.begin(), line.end(), kLink);
           it != std::sregex_iterator();
           ++it) {
        links[command].push_back((*it)[1].str());
      }
    }
  }
  for (const auto& [name, anchors] : links) {
    for (const std::string& anchor : anchors) {
      EXPECT_EQ(groups.count(anchor), 1u) << "no group for #" << anchor;
      for (const auto& row : groups[anchor]) commands[name].insert(row);
    }
  }
  return commands;
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
