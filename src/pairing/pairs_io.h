#pragma once

#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "scene/database.h"
#include "scene/two_view_geometry_store.h"
#include "util/types.h"

namespace colmap_gcn {

// COLMAP 3.8's pairs file (matches_importer --match_type pairs): one
// `name1 name2` per line, split on a single space; `#` and empty lines are
// skipped; a third column is ignored by COLMAP (we use it for scores).

typedef std::pair<std::string, std::string> ImageNamePair;

// Reads a pairs file the way COLMAP 3.8 parses it. Throws Error if the file
// cannot be read or a line has fewer than two names.
std::vector<ImageNamePair> ReadPairsFile(const std::string& path);

// Throws Error if COLMAP's parser would split or mangle the name (space, tab,
// newline, carriage return, or empty).
void CheckPairsFileImageName(const std::string& name);

// Image names of id pairs as a pairs file spells them (COLMAP's, hloc's,
// the raw match list): Of() throws Error for an id not in `images` or a
// name the file cannot hold (CheckPairsFileImageName). Keeps pointers into
// `images`.
class PairFileNames {
 public:
  explicit PairFileNames(const std::vector<DatabaseImage>& images);

  std::pair<const std::string&, const std::string&> Of(
      const ImagePair& pair) const;

 private:
  std::unordered_map<image_t, const std::string*> id_to_name_;
};

// Writes pairs (by image id) as names, one pair a line, atomically. If scores
// is non-empty it must be parallel to pairs and becomes the third column.
void WritePairsFile(const std::string& path,
                    const std::vector<ImagePair>& pairs,
                    const std::vector<DatabaseImage>& images,
                    const std::vector<float>& scores = {});

// Writes COLMAP's raw match list (`matches_importer --match_type raw`),
// atomically: for each pair its two names, one "index1 index2" line per
// match (matches[i] parallel to pairs[i], column 0 indexing pairs[i].first),
// then an empty line.
void WriteRawMatchesFile(const std::string& path,
                         const std::vector<ImagePair>& pairs,
                         const std::vector<FeatureMatches>& matches,
                         const std::vector<DatabaseImage>& images);

}  // namespace colmap_gcn
