#pragma once

namespace colmap_gcn {

// `colmap gcn_pair_filter --database_path db.db [--restore 1]`: the
// look-alike filter alone on a database matched by anything; hides the
// duplicate-structure pairs from COLMAP's mapper and reports them, or puts
// every hidden pair back (docs/lookalike.md).
int RunGcnPairFilter(int argc, char** argv);

}  // namespace colmap_gcn
