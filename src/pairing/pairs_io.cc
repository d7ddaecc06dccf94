#include "pairing/pairs_io.h"

#include <iomanip>
#include <sstream>
#include <unordered_map>

#include "util/error.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {

std::vector<ImageNamePair> ReadPairsFile(const std::string& path) {
  if (!ExistsFile(path)) {
    ThrowError("pairs file not found: ", path);
  }
  std::istringstream lines(ReadTextFile(path));
  std::vector<ImageNamePair> pairs;
  std::string line;
  size_t line_number = 0;
  while (std::getline(lines, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') {
      line.pop_back();
    }
    if (StringTrim(line).empty() || line[0] == '#') {
      continue;
    }
    // COLMAP splits on single spaces; a double space yields an empty name.
    const std::vector<std::string> fields = StringSplit(line, " ");
    if (fields.size() < 2 || fields[0].empty() || fields[1].empty()) {
      ThrowError(path,
                 ":",
                 line_number,
                 ": expected `name1 name2` separated by one space, got \"",
                 line,
                 "\"");
    }
    pairs.emplace_back(fields[0], fields[1]);
  }
  return pairs;
}

void CheckPairsFileImageName(const std::string& name) {
  if (name.empty()) {
    ThrowError("empty image name cannot be written to a pairs file");
  }
  if (name.find_first_of(" \t\r\n") != std::string::npos) {
    ThrowError("image name \"",
               name,
               "\" contains white space, which COLMAP's pairs file cannot "
               "represent; rename the image");
  }
}

PairFileNames::PairFileNames(const std::vector<DatabaseImage>& images) {
  for (const auto& image : images) {
    id_to_name_.emplace(image.image_id, &image.name);
  }
}

std::pair<const std::string&, const std::string&> PairFileNames::Of(
    const ImagePair& pair) const {
  const auto it1 = id_to_name_.find(pair.first);
  const auto it2 = id_to_name_.find(pair.second);
  if (it1 == id_to_name_.end() || it2 == id_to_name_.end()) {
    ThrowError("pair (",
               pair.first,
               ", ",
               pair.second,
               ") names an image id not in the database");
  }
  CheckPairsFileImageName(*it1->second);
  CheckPairsFileImageName(*it2->second);
  return {*it1->second, *it2->second};
}

void WritePairsFile(const std::string& path,
                    const std::vector<ImagePair>& pairs,
                    const std::vector<DatabaseImage>& images,
                    const std::vector<float>& scores) {
  THROW_CHECK(scores.empty() || scores.size() == pairs.size());
  const PairFileNames names(images);
  std::ostringstream contents;
  contents << std::setprecision(6);
  for (size_t i = 0; i < pairs.size(); ++i) {
    const auto [name1, name2] = names.Of(pairs[i]);
    contents << name1 << ' ' << name2;
    if (!scores.empty()) {
      contents << ' ' << scores[i];
    }
    contents << '\n';
  }
  WriteFileAtomically(path, contents.str());
}

void WriteRawMatchesFile(const std::string& path,
                         const std::vector<ImagePair>& pairs,
                         const std::vector<FeatureMatches>& matches,
                         const std::vector<DatabaseImage>& images) {
  THROW_CHECK(matches.size() == pairs.size());
  const PairFileNames names(images);
  std::string contents;
  for (size_t i = 0; i < pairs.size(); ++i) {
    const auto [name1, name2] = names.Of(pairs[i]);
    contents += name1 + ' ' + name2 + '\n';
    for (Eigen::Index m = 0; m < matches[i].rows(); ++m) {
      contents += std::to_string(matches[i](m, 0)) + ' ' +
                  std::to_string(matches[i](m, 1)) + '\n';
    }
    contents += '\n';
  }
  WriteFileAtomically(path, contents);
}

}  // namespace colmap_gcn
