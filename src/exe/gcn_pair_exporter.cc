#include "exe/gcn_pair_exporter.h"

#include "controllers/pair_export.h"
#include "controllers/pair_generators.h"
#include "util/option_manager.h"
#include "util/string.h"

namespace colmap_gcn {

int RunGcnPairExporter(int argc, char** argv) {
  std::string database_path;
  GcnMatchingOptions options;
  // The exporter matches nothing, so its default is the single-shot GCN
  // (the default adaptive pairing needs verifications).
  options.pairing = "gcn";
  PairExportOptions export_options;
  OptionManager manager(
      "gcn_pair_exporter",
      "Writes the pairs a generator chooses, without matching them: hloc's "
      "`query db` lines (for hloc's match_features) or COLMAP's pairs file.");
  manager.AddRequiredOption("database_path", &database_path);
  manager.AddRequiredOption("output_path", &export_options.output_path);
  manager.AddEnumOption("output_format",
                        &export_options.format,
                        PairsFormatNames(),
                        "pairs file layout");
  manager.AddDefaultOption("GcnMatching.pairing",
                           &options.pairing,
                           StringJoin(PairGenerators().Names(), " | "));
  PairGenerators().AddOptions(&manager, &options.generators);
  if (!manager.Parse(argc, argv)) {
    return 0;
  }
  manager.Check([&] {
    options.Check();
    export_options.Check();
  });
  ExportPairs(database_path, options, export_options);
  return 0;
}

}  // namespace colmap_gcn
