#include "exe/colmap.h"

int main(int argc, char** argv) {
  return colmap_gcn::RunColmapFrontend(argc, argv);
}
