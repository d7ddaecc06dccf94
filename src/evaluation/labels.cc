#include "evaluation/labels.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "util/error.h"
#include "util/file.h"
#include "util/option_check.h"
#include "util/string.h"

namespace colmap_gcn {

void PairLabelOptions::Check() const {
  CHECK_OPTION_INTERVAL(min_overlap, 0.0, false, 1.0, true);
  CHECK_OPTION_INTERVAL(min_common_track_ratio, 0.0, false, 1.0, true);
}

PairLabels::PairLabels(const std::vector<std::string>& image_names,
                       bool has_overlap,
                       bool has_common_track_ratio)
    : image_names_(image_names),
      has_overlap_(has_overlap),
      has_common_track_ratio_(has_common_track_ratio) {
  std::sort(image_names_.begin(), image_names_.end());
  image_names_.erase(std::unique(image_names_.begin(), image_names_.end()),
                     image_names_.end());
  for (size_t i = 0; i < image_names_.size(); ++i) {
    image_index_.emplace(image_names_[i], i);
  }
}

bool PairLabels::HasImage(const std::string& name) const {
  return image_index_.count(name) > 0;
}

std::string PairLabels::Key(const std::string& name1,
                            const std::string& name2) {
  // '\n' cannot occur in image names (see CheckPairsFileImageName).
  return name1 < name2 ? name1 + "\n" + name2 : name2 + "\n" + name1;
}

void PairLabels::SetOverlap(const std::string& name1,
                            const std::string& name2,
                            double overlap) {
  if (!has_overlap_) ThrowError("labels from ", source, " have no overlaps");
  if (!IsLabelled(name1, name2)) {
    ThrowError("cannot label pair ", name1, " ", name2, ": unknown image");
  }
  evidence_[Key(name1, name2)].overlap = overlap;
}

void PairLabels::SetCommonTrackRatio(const std::string& name1,
                                     const std::string& name2,
                                     double ratio) {
  if (!has_common_track_ratio_) {
    ThrowError("labels from ", source, " have no common-track ratios");
  }
  if (!IsLabelled(name1, name2)) {
    ThrowError("cannot label pair ", name1, " ", name2, ": unknown image");
  }
  evidence_[Key(name1, name2)].common_track_ratio = ratio;
}

bool PairLabels::IsLabelled(const std::string& name1,
                            const std::string& name2) const {
  return name1 != name2 && HasImage(name1) && HasImage(name2);
}

PairEvidence PairLabels::Evidence(const std::string& name1,
                                  const std::string& name2) const {
  PairEvidence evidence;
  if (!IsLabelled(name1, name2)) return evidence;
  const auto it = evidence_.find(Key(name1, name2));
  if (has_overlap_) {
    evidence.overlap =
        it == evidence_.end() ? 0.0 : std::max(0.0, it->second.overlap);
  }
  if (has_common_track_ratio_) {
    evidence.common_track_ratio =
        it == evidence_.end() ? 0.0
                              : std::max(0.0, it->second.common_track_ratio);
  }
  return evidence;
}

bool PairLabels::IsMatchable(const std::string& name1,
                             const std::string& name2,
                             const PairLabelOptions& options) const {
  const PairEvidence evidence = Evidence(name1, name2);
  return (evidence.overlap >= 0 && evidence.overlap >= options.min_overlap) ||
         (evidence.common_track_ratio >= 0 &&
          evidence.common_track_ratio >= options.min_common_track_ratio);
}

bool PairLabels::SharesNothing(const std::string& name1,
                               const std::string& name2) const {
  if (!IsLabelled(name1, name2)) return false;
  const PairEvidence evidence = Evidence(name1, name2);
  return evidence.overlap <= 0 && evidence.common_track_ratio <= 0;
}

std::vector<ImageNamePair> PairLabels::MatchablePairs(
    const PairLabelOptions& options) const {
  std::vector<ImageNamePair> pairs;
  for (const auto& [key, evidence] : evidence_) {
    const size_t split = key.find('\n');
    const std::string name1 = key.substr(0, split);
    const std::string name2 = key.substr(split + 1);
    if (IsMatchable(name1, name2, options)) pairs.emplace_back(name1, name2);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

void PairLabels::Write(const std::string& path) const {
  std::ostringstream out;
  out << "# source," << source << "\n";
  out << "# kinds," << (has_overlap_ ? 1 : 0) << ","
      << (has_common_track_ratio_ ? 1 : 0) << "\n";
  for (const auto& name : image_names_) out << "image," << name << "\n";
  out << "name1,name2,overlap,common_track_ratio\n";
  std::vector<std::pair<std::string, PairEvidence>> rows(evidence_.begin(),
                                                         evidence_.end());
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) {
    return a.first < b.first;
  });
  char buffer[64];
  for (const auto& [key, evidence] : rows) {
    const size_t split = key.find('\n');
    std::snprintf(buffer,
                  sizeof(buffer),
                  "%.9g,%.9g",
                  evidence.overlap,
                  evidence.common_track_ratio);
    out << key.substr(0, split) << "," << key.substr(split + 1) << "," << buffer
        << "\n";
  }
  WriteFileAtomically(path, out.str());
}

PairLabels PairLabels::Read(const std::string& path) {
  std::istringstream in(ReadTextFile(path));
  std::string line;
  std::string source;
  bool has_overlap = false;
  bool has_ct = false;
  std::vector<std::string> names;
  std::vector<std::vector<std::string>> rows;
  bool header_seen = false;
  size_t line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty()) continue;
    if (StringStartsWith(line, "# source,")) {
      source = line.substr(9);
    } else if (StringStartsWith(line, "# kinds,")) {
      const auto fields = StringSplit(line.substr(8), ",");
      if (fields.size() != 2) ThrowError(path, ":", line_number, ": bad kinds");
      has_overlap = fields[0] == "1";
      has_ct = fields[1] == "1";
    } else if (StringStartsWith(line, "image,")) {
      names.push_back(line.substr(6));
    } else if (StringStartsWith(line, "name1,")) {
      header_seen = true;
    } else {
      const auto fields = StringSplit(line, ",");
      if (!header_seen || fields.size() != 4) {
        ThrowError(path, ":", line_number, ": malformed label line");
      }
      rows.push_back(fields);
    }
  }
  if (!header_seen) ThrowError(path, ": not a pair label file");
  PairLabels labels(names, has_overlap, has_ct);
  labels.source = source;
  for (const auto& row : rows) {
    if (!labels.IsLabelled(row[0], row[1])) {
      ThrowError(path, ": pair ", row[0], " ", row[1], " of unknown images");
    }
    PairEvidence& evidence = labels.evidence_[Key(row[0], row[1])];
    evidence.overlap = std::stod(row[2]);
    evidence.common_track_ratio = std::stod(row[3]);
  }
  return labels;
}

}  // namespace colmap_gcn
