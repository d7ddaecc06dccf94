#include "util/project_file.h"

#include <fstream>

#include "util/error.h"
#include "util/string.h"

namespace colmap_gcn {

std::vector<ProjectFileOption> ReadProjectFile(const std::string& path) {
  std::ifstream file(path);
  if (!file) {
    ThrowError("cannot read the project file --project_path ", path);
  }
  std::vector<ProjectFileOption> options;
  std::string section;
  std::string text;
  for (int line = 1; std::getline(file, text); ++line) {
    text = StringTrim(text);
    if (text.empty() || text[0] == '#' || text[0] == ';') continue;
    if (text.front() == '[') {
      if (text.back() != ']' || text.size() < 3) {
        ThrowError(path, ":", line, ": malformed section header ", text);
      }
      section = StringTrim(text.substr(1, text.size() - 2)) + ".";
      continue;
    }
    const size_t equals = text.find('=');
    if (equals == std::string::npos || equals == 0) {
      ThrowError(path, ":", line, ": expected key=value, got ", text);
    }
    ProjectFileOption option;
    option.name = section + StringTrim(text.substr(0, equals));
    option.value = StringTrim(text.substr(equals + 1));
    option.line = line;
    options.push_back(option);
  }
  return options;
}

std::string FindArgument(const std::vector<std::string>& args,
                         const std::string& name) {
  const std::string flag = "--" + name;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == flag && i + 1 < args.size()) return args[i + 1];
    if (StringStartsWith(args[i], flag + "=")) {
      return args[i].substr(flag.size() + 1);
    }
  }
  return "";
}

}  // namespace colmap_gcn
