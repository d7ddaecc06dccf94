#pragma once

namespace colmap_gcn {

// `colmap gcn_adaptive_simulator`: replays a pair generator that uses
// verification (adaptive, graphmatch) on an exhaustively matched database,
// "matching" a pair by looking up its two_view_geometries row, and compares
// it with single-shot GCN and kNN pair sets of the same size.
int RunGcnAdaptiveSimulator(int argc, char** argv);

}  // namespace colmap_gcn
