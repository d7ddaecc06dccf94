// COLMAP 3.8 steps that hit a full disk or an I/O error. COLMAP logs
// `SQLite error ... database or disk is full` and still exits 0, and its
// mapper writes truncated models without a word, so our commands must check
// what each step was meant to write. Each case runs one of our commands with
// a write failure injected into the real COLMAP it drives (fault_injector.c,
// LD_PRELOAD) and checks that the command fails with one `ERROR:` line, that
// the user's data is as before or complete (never half-written), and that a
// run without the fault ends as an uninterrupted run.

#include <cstring>
#include <filesystem>
#include <map>
#include <regex>
#include <set>

#include <gtest/gtest.h>

#include "e2e_scene.h"
#include "scene/colmap_scene_fixture.h"
#include "scene/database.h"
#include "scene/database_inspector.h"
#include "scene/reconstruction.h"
#include "scene/reconstruction_stats.h"
#include "test_utils.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

namespace fs = std::filesystem;
using test::DatabaseInspector;
using test::GeometryPairIds;
using test::IntegrityCheck;
using test::QuerySqlInt;
using test::RealColmapExe;
using test::RunFrontend;
using test::RunShell;
using test::TwoViewGeometry;

const int kNumImages = 8;
const int kNumPairs = kNumImages * (kNumImages - 1) / 2;
const int kBlockSize = 5;
// Past the -shm set-up and the WAL header: the first page COLMAP writes.
const uint64_t kEarlyBytes = 100;
const uint64_t kUnlimitedBytes = uint64_t{1} << 60;

// A write failure for the real COLMAP under one of our commands.
struct Fault {
  std::string path;  // files whose path contains this
  uint64_t after_bytes = 0;
  std::string error = "ENOSPC";  // ENOSPC | EIO
  std::string log_path;          // one line per failed call
  std::string counter_path;      // the byte count, shared by COLMAP runs
};

std::string FaultEnvironment(const Fault& fault) {
  return "LD_PRELOAD=" + ShellQuote(COLMAP_GCN_FAULT_INJECTOR) +
         " COLMAP_GCN_FAULT_EXE=" + ShellQuote(RealColmapExe()) +
         " COLMAP_GCN_FAULT_PATH=" + ShellQuote(fault.path) +
         " COLMAP_GCN_FAULT_AFTER_BYTES=" + std::to_string(fault.after_bytes) +
         " COLMAP_GCN_FAULT_ERRNO=" + fault.error +
         " COLMAP_GCN_FAULT_LOG=" + ShellQuote(fault.log_path) +
         " COLMAP_GCN_FAULT_COUNTER=" + ShellQuote(fault.counter_path);
}

std::string ReadIfExists(const std::string& path) {
  return ExistsFile(path) ? ReadTextFile(path) : "";
}

// The bytes the injector let through (its shared counter).
uint64_t BytesWritten(const Fault& fault) {
  const std::string counter = ReadIfExists(fault.counter_path);
  uint64_t bytes = 0;
  if (counter.size() == sizeof(bytes)) {
    std::memcpy(&bytes, counter.data(), sizeof(bytes));
  }
  return bytes;
}

std::vector<std::string> ErrorLines(const std::string& output) {
  std::vector<std::string> lines;
  for (const std::string& line : StringSplit(output, "\n")) {
    if (StringStartsWith(line, "ERROR:")) lines.push_back(line);
  }
  return lines;
}

// What the one ERROR line must name for the injected errno.
std::regex CauseOf(const std::string& error) {
  return std::regex(error == "EIO" ? "I/O error" : "disk (is )?full",
                    std::regex::icase);
}

// Pairs by image name: image ids follow COLMAP's extraction order.
std::set<std::string> GeometryPairNames(const std::string& path) {
  const Database database(path);
  std::map<image_t, std::string> names;
  for (const auto& image : database.ReadAllImages()) {
    names[image.image_id] = image.name;
  }
  std::set<std::string> pairs;
  for (const auto& info : database.ReadTwoViewGeometryInfos()) {
    const auto [id1, id2] = PairIdToImagePair(info.pair_id);
    pairs.insert(std::min(names[id1], names[id2]) + " " +
                 std::max(names[id1], names[id2]));
  }
  return pairs;
}

// The pairs of an uninterrupted run, and the bytes COLMAP wrote in it.
struct Reference {
  std::set<int64_t> pair_ids;
  uint64_t bytes = 0;
};

// The database after a run: sound, a row per chosen pair, a match row per
// geometry, nothing of ours beside it. Pairs are compared by their rows, not
// by their verification: COLMAP 3.8's RANSAC is not repeatable (two
// uninterrupted runs differ by a few inliers on some pairs), so a pair near
// the inlier threshold may verify in one run and not in the next.
void ExpectCompleteDatabase(const std::string& path,
                            const Reference& reference) {
  EXPECT_EQ(IntegrityCheck(path), "ok");
  EXPECT_EQ(GeometryPairIds(path), reference.pair_ids);
  EXPECT_EQ(QuerySqlInt(path, "SELECT COUNT(*) FROM matches;"),
            static_cast<int64_t>(reference.pair_ids.size()));
  EXPECT_FALSE(fs::exists(path + ".gcn-partial"));
  EXPECT_FALSE(fs::exists(path + ".gcn-lock"));
}

// Images without keypoints or descriptors.
int64_t NumImagesWithoutFeatures(const std::string& path) {
  return QuerySqlInt(
      path,
      "SELECT COUNT(*) FROM images WHERE image_id NOT IN (SELECT image_id "
      "FROM keypoints WHERE rows > 0) OR image_id NOT IN (SELECT image_id "
      "FROM descriptors WHERE rows > 0);");
}

size_t MaxRegistered(const std::string& sparse_path) {
  size_t max_registered = 0;
  for (const std::string& model_path : ListSparseModels(sparse_path)) {
    Reconstruction reconstruction;
    reconstruction.Read(model_path);
    max_registered = std::max(
        max_registered,
        ComputeReconstructionStatistics(reconstruction).num_registered_images);
  }
  return max_registered;
}

class FaultInjection : public testing::Test {
 protected:
  static void SetUpTestSuite();
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  void SetUp() override {
    if (RealColmapExe().empty()) GTEST_SKIP() << "COLMAP not installed";
    ASSERT_NE(dir_, nullptr);
    ASSERT_TRUE(ready_) << "the suite's scene could not be made";
  }

  static std::string Path(const std::string& name) {
    return JoinPaths(dir_->Path(), name);
  }
  static std::string BasePath() { return Path("base.db"); }
  static std::string ImagePath() { return Path("scene/images"); }
  static std::string CopyOfBase(const std::string& name) {
    fs::copy_file(BasePath(), Path(name), fs::copy_options::overwrite_existing);
    return Path(name);
  }

  // A fault on the files containing path, logged and counted in files
  // named after the case.
  static Fault MakeFault(const std::string& name,
                         const std::string& path,
                         const uint64_t after_bytes,
                         const std::string& error = "ENOSPC") {
    Fault fault;
    fault.path = path;
    fault.after_bytes = after_bytes;
    fault.error = error;
    fault.log_path = Path(name + ".fault.log");
    fault.counter_path = Path(name + ".fault.count");
    fs::remove(fault.log_path);
    fs::remove(fault.counter_path);
    return fault;
  }

  // block_size 0: the default, every pair (of a round) in one COLMAP run.
  static std::string MatcherArgs(const std::string& database_path,
                                 const std::string& pairing,
                                 const int block_size = 0) {
    return "gcn_matcher --database_path " + ShellQuote(database_path) + " " +
           pairing +
           (block_size > 0
                ? " --GcnMatching.block_size " + std::to_string(block_size)
                : "") +
           " --GcnMatching.num_threads 1 --SiftMatching.num_threads 1";
  }

  static std::string ReconstructorArgs(const std::string& workspace_path) {
    return "gcn_reconstructor --image_path " + ImagePath() +
           " --workspace_path " + ShellQuote(workspace_path) +
           extraction_args_ +
           " --GcnMatching.pairing exhaustive --GcnMatching.block_size " +
           std::to_string(kBlockSize) +
           " --GcnMatching.num_threads 1 --SiftMatching.num_threads 1"
           " --Mapper.num_threads 1 --Mapper.min_model_size 3";
  }

  // The pairs gcn_matcher writes with pairing on the scene, uninterrupted,
  // and the bytes COLMAP wrote into the working copy (computed once).
  static const Reference& MatcherReference(const std::string& pairing,
                                           int block_size = 0);

  static TemporaryDirectory* dir_;
  static bool ready_;
  static std::string extraction_args_;
  static uint64_t extraction_bytes_;
  static std::map<std::string, Reference>* matcher_references_;
};

TemporaryDirectory* FaultInjection::dir_ = nullptr;
bool FaultInjection::ready_ = false;
std::string FaultInjection::extraction_args_;
uint64_t FaultInjection::extraction_bytes_ = 0;
std::map<std::string, Reference>* FaultInjection::matcher_references_ =
    new std::map<std::string, Reference>;

void FaultInjection::SetUpTestSuite() {
  if (RealColmapExe().empty()) return;
  dir_ = new TemporaryDirectory("colmap_gcn_fault");
  std::string output;
  ASSERT_EQ(RunFrontend("gcn_synth --output_path " + Path("scene") +
                            " --GcnSynth.family ordinary"
                            " --GcnSynth.num_images " +
                            std::to_string(kNumImages) + " --GcnSynth.seed 1",
                        &output),
            0)
      << output;
  // The generator's intrinsics, as a calibrated user passes them.
  Reconstruction gt;
  gt.ReadText(Path("scene/gt"));
  ASSERT_FALSE(gt.cameras.empty());
  std::vector<std::string> params;
  for (const double param : gt.cameras.begin()->second.params) {
    params.push_back(std::to_string(param));
  }
  extraction_args_ =
      " --ImageReader.single_camera 1 --ImageReader.camera_model PINHOLE"
      " --ImageReader.camera_params " +
      StringJoin(params, ",") +
      " --SiftExtraction.max_num_features 512"
      " --SiftExtraction.num_threads 1 --SiftExtraction.use_gpu 0";
  // Under the injector without a limit: the bytes an extraction writes.
  const Fault count = MakeFault("base", BasePath(), kUnlimitedBytes);
  ASSERT_EQ(RunFrontend("feature_extractor --database_path " + BasePath() +
                            " --image_path " + ImagePath() + extraction_args_,
                        &output,
                        FaultEnvironment(count)),
            0)
      << output;
  extraction_bytes_ = BytesWritten(count);
  ASSERT_GT(extraction_bytes_, 2 * kEarlyBytes);
  ASSERT_EQ(Database(BasePath()).NumImages(), static_cast<size_t>(kNumImages));
  ready_ = true;
}

const Reference& FaultInjection::MatcherReference(const std::string& pairing,
                                                  const int block_size) {
  const std::string key = pairing + " " + std::to_string(block_size);
  auto it = matcher_references_->find(key);
  if (it != matcher_references_->end()) return it->second;
  const std::string name =
      "reference" + std::to_string(matcher_references_->size());
  const std::string database = CopyOfBase(name + ".db");
  const Fault count = MakeFault(name, ".gcn-partial", kUnlimitedBytes);
  std::string output;
  Reference reference;
  EXPECT_EQ(
      RunFrontend(
          MatcherArgs(database, pairing), &output, FaultEnvironment(count)),
      0)
      << output;
  EXPECT_TRUE(ReadIfExists(count.log_path).empty());
  reference.pair_ids = GeometryPairIds(database);
  reference.bytes = BytesWritten(count);
  EXPECT_GT(reference.bytes, 2 * kEarlyBytes) << pairing;
  EXPECT_FALSE(reference.pair_ids.empty()) << pairing;
  return matcher_references_->emplace(key, reference).first->second;
}

// The reported case (issue 25): gcn_matcher's COLMAP finds the disk full
// mid-way through the blocks. The database must stay as it was, the error
// must say so, and a run after space was freed resumes the matched blocks.
TEST_F(FaultInjection, DiskFullDuringMatchingKeepsTheDatabaseAndResumes) {
  const std::string pairing = "--GcnMatching.pairing exhaustive";
  const Reference& reference = MatcherReference(pairing, kBlockSize);
  ASSERT_EQ(reference.pair_ids.size(), static_cast<size_t>(kNumPairs));
  const std::string database = CopyOfBase("disk_full.db");
  const std::string before = ReadTextFile(database);
  const Fault fault =
      MakeFault("disk_full", ".gcn-partial", reference.bytes / 2);
  std::string output;
  EXPECT_NE(RunFrontend(MatcherArgs(database, pairing, kBlockSize),
                        &output,
                        FaultEnvironment(fault)),
            0)
      << output;
  ASSERT_FALSE(ReadIfExists(fault.log_path).empty()) << "no fault injected";
  const std::vector<std::string> errors = ErrorLines(output);
  ASSERT_EQ(errors.size(), 1u) << output;
  EXPECT_TRUE(std::regex_search(errors[0], CauseOf("ENOSPC"))) << errors[0];
  EXPECT_EQ(ReadTextFile(database), before) << "the database was replaced";

  // The blocks COLMAP committed before the disk filled are kept in the copy.
  const std::string copy = database + ".gcn-partial";
  ASSERT_TRUE(ExistsFile(copy)) << output;
  const std::set<int64_t> kept = GeometryPairIds(copy);
  EXPECT_GT(kept.size(), 0u);
  EXPECT_LT(kept.size(), static_cast<size_t>(kNumPairs));
  std::map<int64_t, TwoViewGeometry> kept_rows;
  {
    const DatabaseInspector inspector(copy);
    for (const int64_t pair_id : kept) {
      const auto [id1, id2] = PairIdToImagePair(pair_id);
      kept_rows[pair_id] = inspector.ReadTwoViewGeometry(id1, id2);
    }
  }

  ASSERT_EQ(RunFrontend(MatcherArgs(database, pairing, kBlockSize), &output), 0)
      << output;
  EXPECT_NE(output.find("resuming the interrupted matching"), std::string::npos)
      << output;
  EXPECT_NE(output.find("(" + std::to_string(kept.size()) + " of " +
                        std::to_string(kNumPairs) + " pairs were matched"),
            std::string::npos)
      << output;
  ExpectCompleteDatabase(database, reference);
  const DatabaseInspector after(database);
  for (const auto& [pair_id, row] : kept_rows) {
    const auto [id1, id2] = PairIdToImagePair(pair_id);
    const TwoViewGeometry now = after.ReadTwoViewGeometry(id1, id2);
    EXPECT_EQ(now.config, row.config) << pair_id;
    EXPECT_EQ(now.inlier_matches, row.inlier_matches) << pair_id;
  }
}

// One write failure in the sweep: the COLMAP step, where in its writes,
// and the errno.
struct SweepCase {
  std::string step;  // a pairing under gcn_matcher, or extractor | mapper
  bool mid_way;      // else early: the first page
  std::string error;
};

void PrintTo(const SweepCase& sweep_case, std::ostream* stream) {
  *stream << sweep_case.step << (sweep_case.mid_way ? " mid-way " : " early ")
          << sweep_case.error;
}

std::string SweepCaseName(const testing::TestParamInfo<SweepCase>& info) {
  return info.param.step + (info.param.mid_way ? "_MidWay_" : "_Early_") +
         info.param.error;
}

class FaultSweep : public FaultInjection,
                   public testing::WithParamInterface<SweepCase> {
 protected:
  std::string CaseName() const {
    return SweepCaseName(testing::TestParamInfo<SweepCase>(GetParam(), 0));
  }

  // The failed run's common promises: it failed, with one ERROR line that
  // names the cause when COLMAP reported one, after the fault fired.
  void ExpectReportedFailure(const int exit_code,
                             const std::string& output,
                             const Fault& fault,
                             const bool cause_known) {
    EXPECT_NE(exit_code, 0) << output;
    EXPECT_FALSE(ReadIfExists(fault.log_path).empty()) << "no fault injected";
    const std::vector<std::string> errors = ErrorLines(output);
    ASSERT_EQ(errors.size(), 1u) << output;
    if (cause_known) {
      EXPECT_TRUE(std::regex_search(errors[0], CauseOf(fault.error)))
          << errors[0];
    }
  }

  void RunMatcherCase(const std::string& pairing);
  void RunReconstructorCase(bool fault_the_mapper);
};

void FaultSweep::RunMatcherCase(const std::string& pairing) {
  const Reference& reference = MatcherReference(pairing);
  const std::string database = CopyOfBase(CaseName() + ".db");
  const std::string before = ReadTextFile(database);
  const Fault fault =
      MakeFault(CaseName(),
                ".gcn-partial",
                GetParam().mid_way ? reference.bytes / 2 : kEarlyBytes,
                GetParam().error);
  std::string output;
  const int exit_code = RunFrontend(
      MatcherArgs(database, pairing), &output, FaultEnvironment(fault));
  ExpectReportedFailure(exit_code, output, fault, /*cause_known=*/true);
  // As before, or complete when the fault came after COLMAP's last row.
  if (ReadTextFile(database) != before) {
    ExpectCompleteDatabase(database, reference);
  }

  ASSERT_EQ(RunFrontend(MatcherArgs(database, pairing), &output), 0) << output;
  ExpectCompleteDatabase(database, reference);
}

void FaultSweep::RunReconstructorCase(const bool fault_the_mapper) {
  // The uninterrupted run, once; its mapper's bytes under the injector.
  static Reference* reference = nullptr;
  static size_t reference_registered = 0;
  static std::set<std::string> reference_pairs;
  const std::string reference_workspace = Path("reference_workspace");
  if (reference == nullptr) {
    reference = new Reference;
    const Fault count = MakeFault("reference_workspace",
                                  JoinPaths(reference_workspace, "sparse"),
                                  kUnlimitedBytes);
    std::string output;
    ASSERT_EQ(RunFrontend(ReconstructorArgs(reference_workspace),
                          &output,
                          FaultEnvironment(count)),
              0)
        << output;
    reference->bytes = BytesWritten(count);
    reference_registered =
        MaxRegistered(JoinPaths(reference_workspace, "sparse"));
    reference_pairs =
        GeometryPairNames(JoinPaths(reference_workspace, "database.db"));
  }
  // 8 views of the ordinary family register 3 at a time, in every run.
  ASSERT_GE(reference_registered, 3u);
  ASSERT_EQ(reference_pairs.size(), static_cast<size_t>(kNumPairs));

  const std::string workspace = Path(CaseName());
  const std::string database = JoinPaths(workspace, "database.db");
  const std::string sparse = JoinPaths(workspace, "sparse");
  if (fault_the_mapper) {
    // Features and matches of the uninterrupted run, so that this run's
    // extraction and matching find nothing left to do: only the mapper's
    // writes are faulted.
    CreateDirIfNotExists(workspace);
    fs::copy_file(JoinPaths(reference_workspace, "database.db"), database);
  }
  const uint64_t total =
      fault_the_mapper ? reference->bytes : extraction_bytes_;
  ASSERT_GT(total, 2 * kEarlyBytes);
  const Fault fault = MakeFault(CaseName(),
                                fault_the_mapper ? sparse : database,
                                GetParam().mid_way ? total / 2 : kEarlyBytes,
                                GetParam().error);
  std::string output;
  const int exit_code = RunFrontend(
      ReconstructorArgs(workspace), &output, FaultEnvironment(fault));
  // The mapper says nothing of its failed writes; only SQLite names them.
  ExpectReportedFailure(exit_code, output, fault, !fault_the_mapper);
  if (ExistsFile(database)) {
    EXPECT_EQ(IntegrityCheck(database), "ok");
    EXPECT_EQ(NumImagesWithoutFeatures(database), 0);
  }
  // No model is left that cannot be read.
  for (const std::string& model_path : ListSparseModels(sparse)) {
    Reconstruction reconstruction;
    EXPECT_NO_THROW(reconstruction.Read(model_path)) << model_path;
  }

  ASSERT_EQ(RunFrontend(ReconstructorArgs(workspace), &output), 0) << output;
  EXPECT_EQ(NumImagesWithoutFeatures(database), 0);
  EXPECT_EQ(Database(database).NumImages(), static_cast<size_t>(kNumImages));
  EXPECT_EQ(GeometryPairNames(database), reference_pairs);
  EXPECT_EQ(MaxRegistered(sparse), reference_registered);
}

TEST_P(FaultSweep, FailsWithOneErrorAndTheRerunCompletes) {
  const std::string& step = GetParam().step;
  if (step == "extractor" || step == "mapper") {
    RunReconstructorCase(step == "mapper");
  } else if (step == "imported") {
    // Each image with its two successors.
    const std::vector<DatabaseImage> images =
        Database(BasePath()).ReadAllImages();
    std::string pairs;
    for (size_t i = 0; i < images.size(); ++i) {
      for (size_t j = i + 1; j < std::min(images.size(), i + 3); ++j) {
        pairs += images[i].name + " " + images[j].name + "\n";
      }
    }
    const std::string pairs_path = Path("imported_pairs.txt");
    WriteFileAtomically(pairs_path, pairs);
    RunMatcherCase(
        "--GcnMatching.pairing imported --GcnMatching.match_list_path " +
        pairs_path);
  } else if (step == "adaptive") {
    RunMatcherCase(
        "--GcnMatching.pairing adaptive --GcnMatching.round_size 10");
  } else if (step == "gcn") {
    RunMatcherCase("");  // the default: the GCN with the shipped model
  } else {
    RunMatcherCase("--GcnMatching.pairing " + step);
  }
}

// Every fault in every COLMAP step we drive: matches_importer once per
// matching path (a pair set, exhaustive; rounds, adaptive), feature_extractor
// and mapper. The gcn and imported pairings take the exhaustive path with
// other pairs, so one fault each shows their pairs reach it (CI time).
std::vector<SweepCase> AllSweepCases() {
  std::vector<SweepCase> cases;
  for (const char* step : {"exhaustive", "adaptive", "extractor", "mapper"}) {
    for (const bool mid_way : {false, true}) {
      for (const char* error : {"ENOSPC", "EIO"}) {
        cases.push_back({step, mid_way, error});
      }
    }
  }
  cases.push_back({"gcn", true, "ENOSPC"});
  cases.push_back({"imported", true, "EIO"});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(EveryColmapStep,
                         FaultSweep,
                         testing::ValuesIn(AllSweepCases()),
                         SweepCaseName);

}  // namespace
}  // namespace colmap_gcn
