#include "evaluation/html_report.h"

#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "scene/colmap_scene_fixture.h"
#include "scene/model_writer.h"
#include "test_utils.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

TEST(HtmlReport, EscapesTextAndEncodesBase64) {
  EXPECT_EQ(html::Escape("<a href='x'>\"&\"</a>"),
            "&lt;a href=&#39;x&#39;&gt;&quot;&amp;&quot;&lt;/a&gt;");
  // RFC 4648's test vectors.
  EXPECT_EQ(html::Base64(""), "");
  EXPECT_EQ(html::Base64("f"), "Zg==");
  EXPECT_EQ(html::Base64("fo"), "Zm8=");
  EXPECT_EQ(html::Base64("foo"), "Zm9v");
  EXPECT_EQ(html::Base64("foob"), "Zm9vYg==");
  EXPECT_EQ(html::Base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(html::Base64(std::string("\xff\x00\x80", 3)), "/wCA");
}

TEST(HtmlReport, TablesSortOnAClickWithoutTheNetwork) {
  const std::string table =
      html::SortableTable({"a", "b"}, {{"1", "x"}, {"2", "y"}});
  EXPECT_NE(table.find("<table class=\"sortable\">"), std::string::npos);
  EXPECT_NE(table.find("<td>2</td><td>y</td>"), std::string::npos);
  const std::string page = html::Page("t<", table);
  EXPECT_NE(page.find("<title>t&lt;</title>"), std::string::npos);
  EXPECT_NE(page.find("table.sortable th"), std::string::npos);  // the script
  EXPECT_EQ(page.find("://"), std::string::npos);  // nothing fetched
}

// A gcn_reconstructor workspace made by hand: 5 images, pairs 1-2, 2-3, 3-4
// verified, 4-5 and 1-5 matched but rejected; images 1-4 in one model.
std::string WriteWorkspace(const std::string& dir) {
  const std::string database = JoinPaths(dir, "database.db");
  std::string sql = std::string(test::kColmap38Schema) +
                    "INSERT INTO cameras VALUES (1, 0, 640, 480, "
                    "x'0000000000407F4000000000000074400000000000006E40', 0);";
  for (int i = 1; i <= 5; ++i) {
    sql += "INSERT INTO images(image_id, name, camera_id) VALUES (" +
           std::to_string(i) + ", 'img" + std::to_string(i) + ".jpg', 1);";
  }
  const auto geometry = [&](int a, int b, int config, int rows) {
    sql +=
        "INSERT INTO two_view_geometries(pair_id, rows, cols, data, "
        "config) VALUES (" +
        std::to_string(2147483647LL * a + b) + ", " + std::to_string(rows) +
        ", 2, x'', " + std::to_string(config) + ");";
  };
  geometry(1, 2, 2, 100);
  geometry(2, 3, 2, 80);
  geometry(3, 4, 2, 60);
  geometry(4, 5, 0, 0);
  geometry(1, 5, 2, 5);  // too few inliers
  test::ExecuteSql(database, sql);
  std::ofstream(database + ".pairs.txt")
      << "img1.jpg img2.jpg\nimg2.jpg img3.jpg\nimg3.jpg img4.jpg\n"
         "img4.jpg img5.jpg\nimg1.jpg img5.jpg\n";
  Reconstruction model;
  ModelCamera camera;
  camera.camera_id = 1;
  camera.model_id = 0;  // SIMPLE_PINHOLE
  camera.width = 640;
  camera.height = 480;
  camera.params = {500, 320, 240};
  model.cameras[1] = camera;
  for (int i = 1; i <= 4; ++i) {
    ModelImage image;
    image.image_id = i;
    image.camera_id = 1;
    image.name = "img" + std::to_string(i) + ".jpg";
    image.tvec = Eigen::Vector3d(i, 0, 0);
    model.images[i] = image;
  }
  test::WriteBinaryModel(model, JoinPaths(dir, "sparse/0"));
  Json run;
  run["command"] = "colmap gcn_reconstructor --image_path images";
  run["settings"] = {{"GcnMatching.pairing", "gcn"}};
  run["pairing"] = "gcn";
  run["tam"] = 5;
  run["um"] = 3;
  run["stages"] =
      Json::array({{{"name", "feature extraction"}, {"seconds", 1.5}},
                   {{"name", "mapping"}, {"seconds", 2.0}}});
  WriteJsonFile(JoinPaths(dir, kRunSummaryFile), run);
  return dir;
}

TEST(HtmlReport, ReconstructionPageNamesTheImagesNotRegistered) {
  TemporaryDirectory dir;
  HtmlReportOptions options;
  options.workspace_path = WriteWorkspace(dir.Path());
  const std::string path = WriteHtmlReport(options);
  EXPECT_EQ(path, JoinPaths(dir.Path(), "report.html"));
  const std::string page = ReadTextFile(path);
  EXPECT_NE(page.find("Images not registered (1)"), std::string::npos);
  // img5 was matched with img4 and img1, and neither pair verified.
  EXPECT_NE(page.find("<td>img5.jpg</td><td>2</td><td>0</td>"),
            std::string::npos)
      << page.substr(0, 4000);
  EXPECT_NE(page.find("4 / 5"), std::string::npos);  // registered
  EXPECT_NE(page.find("pairs matched (TAM)"), std::string::npos);
  EXPECT_NE(page.find("0.600"), std::string::npos);  // UM per TAM: 3 / 5
  EXPECT_NE(page.find("feature extraction"), std::string::npos);
  EXPECT_NE(page.find("<b>3.5</b>"), std::string::npos);  // total time
  EXPECT_NE(page.find("src=\"data:image/png;base64,"), std::string::npos);
  EXPECT_EQ(page.find("://"), std::string::npos);  // no URL
  EXPECT_TRUE(ExistsFile(JoinPaths(dir.Path(), "view_graph.png")));
}

TEST(HtmlReport, BenchmarkPageHasThePapersTables) {
  TemporaryDirectory dir;
  Json method;
  method["method"] = "knn:5";
  method["status"] = "ok";
  method["tam"] = 40;
  method["um"] = 30;
  method["um_over_tam"] = 0.75;
  method["retrieval"] = {{"precision", 0.5}, {"recall", 0.8}};
  method["sfm"] = {{"num_images", 10}, {"num_registered", 9}};
  Json scene;
  scene["name"] = "castle";
  scene["methods"] = Json::array({method});
  Json results;
  results["command"] = "colmap gcn_benchmark";
  results["methods"] = Json::array({"knn:5"});
  results["scenes"] = Json::array({scene});
  WriteJsonFile(JoinPaths(dir.Path(), "results.json"), results);
  HtmlReportOptions options;
  options.workspace_path = dir.Path();
  const std::string page = ReadTextFile(WriteHtmlReport(options));
  EXPECT_NE(page.find("Benchmark report"), std::string::npos);
  EXPECT_NE(page.find("Retrieval (the paper's Tables 1-2)"), std::string::npos);
  EXPECT_NE(page.find("<td>castle</td><td>knn:5</td><td>40</td><td>30</td>"),
            std::string::npos);
  // The means: 9 of 10 registered.
  EXPECT_NE(page.find("<td>0.900</td>"), std::string::npos);
}

TEST(HtmlReport, RejectsAFolderThatIsNoWorkspace) {
  TemporaryDirectory dir;
  HtmlReportOptions options;
  options.workspace_path = dir.Path();
  test::ExpectErrorContaining([&] { WriteHtmlReport(options); },
                              "holds neither database.db");
  options.workspace_path = JoinPaths(dir.Path(), "missing");
  test::ExpectErrorContaining([&] { WriteHtmlReport(options); },
                              "is not a folder");
}

// Debian's Chromium, or "" when not installed.
std::string ChromiumExe() {
  for (const char* path : {"/usr/bin/chromium", "/usr/bin/chromium-browser"}) {
    if (ExistsFile(path)) return path;
  }
  return "";
}

// The page in a real browser: headless Chromium renders it to a PNG, which
// must show something (not a blank page).
TEST(HtmlReportChromium, RendersInHeadlessChromium) {
  const std::string chromium = ChromiumExe();
  if (chromium.empty()) GTEST_SKIP() << "chromium not installed";
  TemporaryDirectory dir;
  HtmlReportOptions options;
  options.workspace_path = WriteWorkspace(dir.Path());
  const std::string page = WriteHtmlReport(options);
  const std::string png = JoinPaths(dir.Path(), "report.png");
  std::string output;
  const int status = test::RunShell(
      ShellQuote(chromium) +
          " --headless --no-sandbox --disable-gpu --hide-scrollbars "
          "--user-data-dir=" +
          ShellQuote(JoinPaths(dir.Path(), "profile")) +
          " --screenshot=" + ShellQuote(png) + " --window-size=1200,2000 " +
          ShellQuote("file://" + page),
      &output);
  ASSERT_EQ(status, 0) << output;
  const cv::Mat image = cv::imread(png, cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(image.empty()) << "no screenshot: " << output;
  EXPECT_EQ(image.cols, 1200);
  EXPECT_EQ(image.rows, 2000);
  cv::Scalar mean, stddev;
  cv::meanStdDev(image, mean, stddev);
  EXPECT_GT(stddev[0], 10.0) << "a blank page";
  // Text, tables and the view graph: a fair share of non-white pixels.
  EXPECT_GT(cv::countNonZero(image < 200), image.total() / 100);
}

}  // namespace
}  // namespace colmap_gcn
