#pragma once

#include <string>
#include <unordered_map>
#include <vector>

namespace colmap_gcn {

// Ground-truth overlap of one unordered image pair (name1 before name2 in
// the generator's image order). num_visible1 is the number of surface samples
// image 1 sees, num_shared the number both see; overlap12 = num_shared /
// num_visible1 (the fraction of image 1's visible surface that image 2 also
// sees) and overlap21 = num_shared / num_visible2 (0 when a count is 0).
struct PairOverlap {
  std::string name1;
  std::string name2;
  int num_visible1 = 0;
  int num_visible2 = 0;
  int num_shared = 0;
  double overlap12 = 0.0;
  double overlap21 = 0.0;

  double MinOverlap() const {
    return overlap12 < overlap21 ? overlap12 : overlap21;
  }
  double MaxOverlap() const {
    return overlap12 > overlap21 ? overlap12 : overlap21;
  }
};

// The pair table <output>/gt/pair_overlap.csv: a header line
//   name1,name2,num_visible1,num_visible2,num_shared,overlap12,overlap21
// then one line per unordered pair of images (distractors included, with
// zero overlap).
class PairOverlapTable {
 public:
  const std::vector<PairOverlap>& Pairs() const { return pairs_; }
  size_t NumPairs() const { return pairs_.size(); }

  void Add(const PairOverlap& pair);

  // The pair in either order, or nullptr.
  const PairOverlap* Find(const std::string& name_a,
                          const std::string& name_b) const;

  // Fraction of image a's visible surface that image b sees (0 if the pair
  // is unknown).
  double Overlap(const std::string& name_a, const std::string& name_b) const;

 private:
  std::vector<PairOverlap> pairs_;
  std::unordered_map<std::string, size_t> index_;  // "name1\nname2" -> idx
};

// Throws Error naming the file on a missing or malformed table.
PairOverlapTable ReadPairOverlapTable(const std::string& path);
void WritePairOverlapTable(const PairOverlapTable& table,
                           const std::string& path);

}  // namespace colmap_gcn
