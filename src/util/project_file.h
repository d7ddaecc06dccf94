#pragma once

#include <string>
#include <vector>

namespace colmap_gcn {

// One option of a project file: `key=value` on line `line`, under the
// section `[Section]` it follows, named "Section.key" as on the command line.
struct ProjectFileOption {
  std::string name;
  std::string value;
  int line = 0;
};

// Reads a project file in the layout of COLMAP's `--project_path` files
// (`colmap project_generator`): `key=value` lines, `[Section]` headers
// prefixing the keys after them with "Section.", `#` and `;` comment lines
// and empty lines skipped, spaces around keys and values trimmed. Throws
// Error "<path>:<line>: ..." for a line that is none of these, or when the
// file cannot be read.
std::vector<ProjectFileOption> ReadProjectFile(const std::string& path);

// The value of `--<name> V` or `--<name>=V` in args, or "" when absent.
std::string FindArgument(const std::vector<std::string>& args,
                         const std::string& name);

}  // namespace colmap_gcn
