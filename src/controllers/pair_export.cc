#include "controllers/pair_export.h"

#include <sstream>

#include "controllers/pair_generators.h"
#include "pairing/pairs_io.h"
#include "util/error.h"
#include "util/file.h"
#include "util/logging.h"

namespace colmap_gcn {

const EnumNames<PairsFormat>& PairsFormatNames() {
  static const EnumNames<PairsFormat> kNames = {
      {"colmap", PairsFormat::kColmap}, {"hloc", PairsFormat::kHloc}};
  return kNames;
}

void WriteHlocPairsFile(const std::string& path,
                        const std::vector<ImagePair>& pairs,
                        const std::vector<DatabaseImage>& images) {
  // hloc splits lines on white space, like COLMAP.
  const PairFileNames names(images);
  std::ostringstream contents;
  for (const ImagePair& pair : pairs) {
    const auto [name1, name2] = names.Of(pair);
    contents << name1 << ' ' << name2 << '\n';
  }
  WriteFileAtomically(path, contents.str());
}

void PairExportOptions::Check() const {
  if (output_path.empty()) {
    throw OptionError(
        &output_path, "output_path", "must name the pairs file to write", "");
  }
  CheckOutputFolder(output_path);
}

namespace {

[[noreturn]] void ThrowChosenByVerification(const std::string& pairing) {
  ThrowError("--GcnMatching.pairing ",
             pairing,
             " chooses pairs from COLMAP's verification round by round; "
             "run gcn_matcher, then export its pairs file with "
             "--GcnMatching.pairing imported");
}

}  // namespace

size_t ExportPairs(const std::string& database_path,
                   const GcnMatchingOptions& options,
                   const PairExportOptions& export_options) {
  options.Check();
  export_options.Check();
  // Known before minutes of embedding.
  if (PairGenerators().UsesVerification(options.pairing)) {
    ThrowChosenByVerification(options.pairing);
  }
  if (!ExistsFile(database_path)) {
    ThrowError("database not found: ", database_path);
  }
  const Database database(database_path);
  const std::vector<DatabaseImage> images = database.ReadAllImages();
  if (images.size() < 2) {
    ThrowError(database_path,
               " has ",
               images.size(),
               " image(s); pairs need at least 2");
  }
  std::unique_ptr<PairGenerator> generator =
      CreatePairGenerator(options, database);
  const std::vector<ImagePair> pairs = generator->AllPairs();
  const std::string warning = generator->Warning();
  if (!warning.empty()) LOG(WARNING) << warning;
  if (export_options.format == PairsFormat::kHloc) {
    WriteHlocPairsFile(export_options.output_path, pairs, images);
  } else {
    WritePairsFile(
        export_options.output_path, pairs, images, generator->Scores());
  }
  LOG(INFO) << options.pairing << " pairing of " << images.size()
            << " images: " << pairs.size() << " pairs written to "
            << export_options.output_path << " ("
            << EnumName(PairsFormatNames(), export_options.format)
            << " layout)";
  return pairs.size();
}

}  // namespace colmap_gcn
