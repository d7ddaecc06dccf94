#pragma once

#include <string>
#include <vector>

namespace colmap_gcn {

// Our commands (gcn_*), in the order `colmap help` lists them.
std::vector<std::string> GcnCommandNames();

// The `colmap` front end: runs our commands (gcn_*) and hands every other
// command to the real COLMAP with arguments and exit code unchanged.
int RunColmapFrontend(int argc, char** argv);

}  // namespace colmap_gcn
