#pragma once

#include <string>
#include <vector>

#include "controllers/gcn_matching.h"
#include "scene/database.h"
#include "util/option_check.h"
#include "util/types.h"

namespace colmap_gcn {

// The pairs file layouts `gcn_pair_exporter` writes: COLMAP's
// (matches_importer: `name1 name2 [score]`) and hloc's (pairs_from_retrieval:
// `query db`, exactly two names a line, which hloc's parse_retrieval needs).
enum class PairsFormat { kColmap, kHloc };
const EnumNames<PairsFormat>& PairsFormatNames();

// Writes pairs (by image id) as hloc's `query db` lines, atomically, in the
// generator's order; each unordered pair once (hloc matches a pair once in
// either direction).
void WriteHlocPairsFile(const std::string& path,
                        const std::vector<ImagePair>& pairs,
                        const std::vector<DatabaseImage>& images);

struct PairExportOptions {
  // Where the pairs are written.
  std::string output_path = "";

  // Layout of output_path.
  PairsFormat format = PairsFormat::kHloc;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

// Chooses the pairs of options.pairing on the database, read-only and
// without matching anything, and writes them as export_options says; returns
// the number of pairs. Throws Error for generators that choose pairs from
// COLMAP's verification (adaptive, graphmatch): their pairs exist only after
// gcn_matcher has run.
size_t ExportPairs(const std::string& database_path,
                   const GcnMatchingOptions& options,
                   const PairExportOptions& export_options);

}  // namespace colmap_gcn
