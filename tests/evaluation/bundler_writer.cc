#include "evaluation/bundler_writer.h"

#include <sstream>

#include "util/file.h"

namespace colmap_gcn {
namespace test {

void WriteBundlerFile(const std::string& path, const BundlerFile& bundle) {
  std::ostringstream out;
  out.precision(17);
  out << "# Bundle file v0.3\n";
  out << bundle.cameras.size() << " " << bundle.points.size() << "\n";
  for (const BundlerCamera& camera : bundle.cameras) {
    out << camera.focal_length << " " << camera.k1 << " " << camera.k2 << "\n";
    for (int row = 0; row < 3; ++row) {
      out << camera.rotation(row, 0) << " " << camera.rotation(row, 1) << " "
          << camera.rotation(row, 2) << "\n";
    }
    out << camera.translation(0) << " " << camera.translation(1) << " "
        << camera.translation(2) << "\n";
  }
  for (const BundlerPoint& point : bundle.points) {
    out << point.xyz(0) << " " << point.xyz(1) << " " << point.xyz(2) << "\n";
    out << point.color(0) << " " << point.color(1) << " " << point.color(2)
        << "\n";
    out << point.views.size();
    for (const BundlerView& view : point.views) {
      out << " " << view.camera_idx << " " << view.key_idx << " " << view.x
          << " " << view.y;
    }
    out << "\n";
  }
  WriteFileAtomically(path, out.str());
}

}  // namespace test
}  // namespace colmap_gcn
