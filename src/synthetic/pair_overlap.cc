#include "synthetic/pair_overlap.h"

#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "util/error.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

const char kHeader[] =
    "name1,name2,num_visible1,num_visible2,num_shared,overlap12,overlap21";

std::string Key(const std::string& a, const std::string& b) {
  return a + '\n' + b;
}

}  // namespace

void PairOverlapTable::Add(const PairOverlap& pair) {
  index_[Key(pair.name1, pair.name2)] = pairs_.size();
  pairs_.push_back(pair);
}

const PairOverlap* PairOverlapTable::Find(const std::string& name_a,
                                          const std::string& name_b) const {
  auto it = index_.find(Key(name_a, name_b));
  if (it == index_.end()) {
    it = index_.find(Key(name_b, name_a));
  }
  return it == index_.end() ? nullptr : &pairs_[it->second];
}

double PairOverlapTable::Overlap(const std::string& name_a,
                                 const std::string& name_b) const {
  const PairOverlap* pair = Find(name_a, name_b);
  if (pair == nullptr) {
    return 0.0;
  }
  return pair->name1 == name_a ? pair->overlap12 : pair->overlap21;
}

PairOverlapTable ReadPairOverlapTable(const std::string& path) {
  const std::string contents = ReadTextFile(path);
  std::istringstream stream(contents);
  std::string line;
  PairOverlapTable table;
  int line_number = 0;
  bool header_seen = false;
  while (std::getline(stream, line)) {
    ++line_number;
    line = StringTrim(line);
    if (line.empty() || line[0] == '#') {
      continue;
    }
    if (!header_seen) {
      if (line != kHeader) {
        ThrowError(path, ":", line_number, ": expected header '", kHeader, "'");
      }
      header_seen = true;
      continue;
    }
    const std::vector<std::string> fields = StringSplit(line, ",");
    if (fields.size() != 7) {
      ThrowError(
          path, ":", line_number, ": expected 7 fields, got ", fields.size());
    }
    PairOverlap pair;
    pair.name1 = fields[0];
    pair.name2 = fields[1];
    try {
      size_t pos = 0;
      auto to_int = [&](const std::string& s) {
        const int value = std::stoi(s, &pos);
        if (pos != s.size() || value < 0) throw std::invalid_argument(s);
        return value;
      };
      auto to_double = [&](const std::string& s) {
        const double value = std::stod(s, &pos);
        if (pos != s.size() || !(value >= 0.0 && value <= 1.0)) {
          throw std::invalid_argument(s);
        }
        return value;
      };
      pair.num_visible1 = to_int(fields[2]);
      pair.num_visible2 = to_int(fields[3]);
      pair.num_shared = to_int(fields[4]);
      pair.overlap12 = to_double(fields[5]);
      pair.overlap21 = to_double(fields[6]);
    } catch (const std::exception&) {
      ThrowError(path, ":", line_number, ": malformed number in '", line, "'");
    }
    if (pair.name1.empty() || pair.name2.empty()) {
      ThrowError(path, ":", line_number, ": empty image name");
    }
    table.Add(pair);
  }
  if (!header_seen) {
    ThrowError(path, ": missing header line");
  }
  return table;
}

void WritePairOverlapTable(const PairOverlapTable& table,
                           const std::string& path) {
  std::string contents = std::string(kHeader) + "\n";
  char buffer[128];
  for (const PairOverlap& pair : table.Pairs()) {
    std::snprintf(buffer,
                  sizeof(buffer),
                  ",%d,%d,%d,%.6f,%.6f\n",
                  pair.num_visible1,
                  pair.num_visible2,
                  pair.num_shared,
                  pair.overlap12,
                  pair.overlap21);
    contents += pair.name1 + "," + pair.name2 + buffer;
  }
  WriteFileAtomically(path, contents);
}

}  // namespace colmap_gcn
