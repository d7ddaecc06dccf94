#pragma once

namespace colmap_gcn {

// The `colmap` front end: runs our commands (gcn_*) and hands every other
// command to the real COLMAP with arguments and exit code unchanged.
int RunColmapFrontend(int argc, char** argv);

}  // namespace colmap_gcn
