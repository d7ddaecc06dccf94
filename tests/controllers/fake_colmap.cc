#include "fake_colmap.h"

#include <sys/stat.h>

#include <fstream>

#include "scene/colmap_scene_fixture.h"
#include "scene/database_copy.h"
#include "test_utils.h"
#include "util/error.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace test {

FakeColmap::FakeColmap(const std::string& dir)
    : dir_(dir), exe_(JoinPaths(dir, "colmap")) {
  const std::string args_path = ShellQuote(JoinPaths(dir_, "args.txt"));
  const std::string fail_path = ShellQuote(JoinPaths(dir_, "fail"));
  const std::string template_path = ShellQuote(JoinPaths(dir_, "template.db"));
  const std::string output_path = ShellQuote(JoinPaths(dir_, "output.txt"));
  const std::string skip_path = ShellQuote(JoinPaths(dir_, "skip"));
  const std::string truncate_path = ShellQuote(JoinPaths(dir_, "truncate"));
  std::ofstream script(exe_);
  script << "#!/bin/sh\n"
            "if [ \"$1\" = help ]; then echo 'COLMAP 3.8 (fake)'; exit 0; fi\n"
            "printf '%s\\n' \"$@\" > "
         << args_path << "\nif [ -e " << fail_path
         << " ]; then echo 'fake failure'; exit 1; fi\n"
            "if [ -e "
         << output_path << " ]; then cat " << output_path
         << "; fi\n"
            "if [ -e "
         << skip_path
         << " ]; then exit 0; fi\n"
            "prev=\n"
            "for arg in \"$@\"; do\n"
            "  case \"$prev\" in\n"
            "    --database_path) db=\"$arg\" ;;\n"
            "    --output_path) out=\"$arg\" ;;\n"
            "  esac\n"
            "  prev=\"$arg\"\n"
            "done\n"
            "case \"$1\" in\n"
            "  feature_extractor) cp "
         << template_path
         << " \"$db\" ;;\n"
            "  mapper) mkdir -p \"$out/0\"\n"
            "    echo '1 PINHOLE 640 480 500 500 320 240' > "
            "\"$out/0/cameras.txt\"\n"
            "    : > \"$out/0/images.txt\"; : > \"$out/0/points3D.txt\"\n"
            "    if [ -e "
         << truncate_path
         << " ]; then rm \"$out/0\"/*.txt\n"
            "      printf '\\001' > \"$out/0/cameras.bin\"\n"
            "      : > \"$out/0/images.bin\"; : > \"$out/0/points3D.bin\"\n"
            "    fi ;;\n"
            "esac\n";
  script.close();
  if (!script || chmod(exe_.c_str(), 0755) != 0) {
    ThrowError("cannot write ", exe_);
  }
  SetExtractedImages(2);
}

ColmapRunner FakeColmap::Runner() const {
  ColmapRunnerOptions options;
  options.colmap_exe = exe_;
  options.show_progress = false;
  return ColmapRunner(options);
}

std::vector<std::string> FakeColmap::LastArguments() const {
  const std::string path = JoinPaths(dir_, "args.txt");
  if (!ExistsFile(path)) return {};
  std::vector<std::string> args;
  std::ifstream file(path);
  for (std::string line; std::getline(file, line);) args.push_back(line);
  return args;
}

void FakeColmap::SetExtractedImages(const int num_images) const {
  const std::string path = JoinPaths(dir_, "template.db");
  RemoveDatabaseFiles(path);
  std::string sql = std::string(kColmap38Schema) +
                    "INSERT INTO cameras VALUES (1, 0, 640, 480, "
                    "x'0000000000407F4000000000000074400000000000006E40', 0);";
  for (int i = 1; i <= num_images; ++i) {
    const std::string id = std::to_string(i);
    // Zero features each: rows as COLMAP writes them for a featureless
    // image, so the extraction reads back as complete.
    sql += "INSERT INTO images (image_id, name, camera_id) VALUES (" + id +
           ", 'img" + id +
           ".jpg', 1);"
           "INSERT INTO keypoints VALUES (" +
           id +
           ", 0, 6, x'');"
           "INSERT INTO descriptors VALUES (" +
           id + ", 0, 128, x'');";
  }
  ExecuteSql(path, sql);
}

void FakeColmap::FailRuns() const {
  std::ofstream(JoinPaths(dir_, "fail")) << "1\n";
}

void FakeColmap::PrintOnEveryRun(const std::string& text) const {
  std::ofstream(JoinPaths(dir_, "output.txt")) << text;
}

void FakeColmap::SkipWrites() const {
  std::ofstream(JoinPaths(dir_, "skip")) << "1\n";
}

void FakeColmap::WriteTruncatedModels() const {
  std::ofstream(JoinPaths(dir_, "truncate")) << "1\n";
}

void FakeColmap::SetImagesWithoutFeatures(const int num_images) const {
  SetExtractedImages(num_images);
  ExecuteSql(JoinPaths(dir_, "template.db"),
             "DELETE FROM descriptors WHERE image_id = " +
                 std::to_string(num_images) + ";");
}

}  // namespace test
}  // namespace colmap_gcn
