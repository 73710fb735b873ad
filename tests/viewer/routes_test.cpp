// What the viewer's addresses answer in a replay: the page's files by plain name only, the JSON
// of the session, model and frames, and clear errors for the rest.
#include "viewer/routes.hpp"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "run_file/run_file_writer.hpp"

namespace tongue::viewer {
namespace {

namespace fs = std::filesystem;

class ReplayRoutes : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("viewer_routes_" + std::to_string(::getpid()));
    fs::create_directories(dir_ / "web");
    std::ofstream(dir_ / "web" / "index.html") << "<!doctype html>";
    std::ofstream(dir_ / "secret.txt") << "not served";
    run_ = (dir_ / "run.h5").string();
    write_run();
    replay_ = std::make_unique<RunReplay>(std::vector<std::string>{run_});
    routes_ = std::make_unique<Routes>((dir_ / "web").string(), replay_.get(), nullptr);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A one-hexahedron run of two frames, the second moved by 1 mm along x.
  void write_run() {
    run_file::MeshDescription mesh;
    mesh.nodes = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                  {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    mesh.elements = {{0, 1, 2, 3, 4, 5, 6, 7}};
    run_file::RunFileWriter w(run_, mesh, "scene: text", {}, {}, {});
    Eigen::VectorXd x(24);
    for (int i = 0; i < 8; ++i)
      x.segment<3>(3 * i) = Eigen::Map<const Eigen::Vector3d>(mesh.nodes[i].data());
    w.append(0.0, x, {}, {});
    x(0) += 0.001;
    w.append(0.004, x, {}, {});
  }

  nlohmann::json json(const std::string& target, unsigned status = 200) {
    const HttpAnswer a = routes_->answer(target);
    EXPECT_EQ(a.status, status) << target << ": " << a.body;
    return nlohmann::json::parse(a.body);
  }

  fs::path dir_;
  std::string run_;
  std::unique_ptr<RunReplay> replay_;
  std::unique_ptr<Routes> routes_;
};

TEST_F(ReplayRoutes, ServesThePageAndThreeJs) {
  EXPECT_EQ(routes_->answer("/").body, "<!doctype html>");
  EXPECT_EQ(routes_->answer("/index.html").content_type, "text/html; charset=utf-8");
  const HttpAnswer three = routes_->answer("/three/three.min.js");
  EXPECT_EQ(three.status, 200u);
  EXPECT_NE(three.body.find("REVISION"), std::string::npos);
}

TEST_F(ReplayRoutes, NothingOutsideThePagesFolder) {
  for (const char* target : {"/../secret.txt", "/..%2fsecret.txt", "/.hidden", "/web/index.html",
                             "//etc/passwd", "/missing.js"})
    EXPECT_EQ(routes_->answer(target).status, 404u) << target;
}

TEST_F(ReplayRoutes, SessionModelAndFrames) {
  const auto session = json("/api/session");
  EXPECT_EQ(session["mode"], "replay");
  EXPECT_EQ(session["runs"][0]["frames"], 2);
  EXPECT_EQ(session["runs"][0]["times"], (std::vector<double>{0.0, 0.004}));
  const auto model = json("/api/model?run=0");
  EXPECT_EQ(model["num_nodes"], 8);
  EXPECT_EQ(model["surface"].size(), 24u);
  const auto frame = json("/api/frame?run=0&index=1");
  EXPECT_EQ(frame["index"], 1);
  EXPECT_DOUBLE_EQ(frame["time"].get<double>(), 0.004);
  EXPECT_DOUBLE_EQ(frame["positions"][0].get<double>(), 0.001);
}

TEST_F(ReplayRoutes, BadFrameRequestsAreAnsweredWithAReason) {
  EXPECT_EQ(json("/api/frame?run=0&index=2", 404)["error"], "run 0 has 2 frames, no frame 2");
  EXPECT_EQ(json("/api/frame?run=1&index=0", 404)["error"], "no run 1");
  for (const char* target : {"/api/frame", "/api/frame?run=0", "/api/frame?run=0&index=-1",
                             "/api/frame?run=0&index=1x", "/api/frame?run=&index="})
    EXPECT_EQ(json(target, 400)["error"], "/api/frame wants run=R&index=I, both numbers") << target;
}

TEST(RunReplay, ABadRunFileIsRefusedNamingIt) {
  const fs::path path =
      fs::temp_directory_path() / ("not_a_run_" + std::to_string(::getpid()) + ".h5");
  std::ofstream(path) << "plain text";
  try {
    RunReplay replay({path.string()});
    ADD_FAILURE() << "accepted a text file";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  fs::remove(path);
}

}  // namespace
}  // namespace tongue::viewer
