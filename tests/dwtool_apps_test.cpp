// dwtool's wavelet applications (edit, combine, decouple, deform) as scripts use them: an edit with
// all factors 1 gives the input back exactly on both backends, the outputs are written, and bad
// input gives exactly one "dwtool: " line, exit code 1 and no output file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "imageio/read.h"
#include "imageio/write.h"
#include "support/scratch_dir.h"
#include "testimages/patterns.h"
#include "wavelet_apps/control_net.h"

#ifndef DWTOOL_PATH
#error "DWTOOL_PATH must name the dwtool binary (see tests/CMakeLists.txt)"
#endif

namespace fs = std::filesystem;

namespace {

struct Result {
  int exit_code = -1;
  std::string err;
};

Result dwtool(const test_support::ScratchDir& dir, const std::string& args) {
  const fs::path err = dir / "stderr.txt";
  const int status = std::system((std::string(DWTOOL_PATH) + " " + args + " >/dev/null 2>" + err.string()).c_str());
  Result r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  r.err = text.str();
  return r;
}

// Appending, not operator+ on a literal: GCC 12 reports a false -Wrestrict for the latter.
std::string quoted(const fs::path& p) {
  std::string text(1, '\'');
  text += p.string();
  text += '\'';
  return text;
}

class DwtoolApps : public ::testing::Test {
 protected:
  void SetUp() override {
    input = dir / "in.png";
    imageio::write_image(input.string(), testimages::generate(testimages::Pattern::Mix, 80, 64, 3, 8));
  }
  test_support::ScratchDir dir{"dwtool_apps"};
  fs::path input;
};

TEST_F(DwtoolApps, EditWithAllFactorsOneGivesTheInputBackExactlyOnBothBackends) {
  for (const char* backend : {"cpu", "gpu"}) {
    const fs::path out = dir / (std::string(backend) + ".png");
    const Result r = dwtool(dir, "edit -i " + quoted(input) + " -o " + quoted(out) +
                                     " --space ycc --levels 4 --band '*=1' --band Y:1:*=keep --backend " + backend);
    if (std::string(backend) == "gpu" && r.exit_code != 0 && r.err.find("GL") != std::string::npos)
      GTEST_SKIP() << "no GL context for --backend gpu here: " << r.err;
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(imageio::read_image(out.string()).pixels, imageio::read_image(input.string()).pixels) << backend;
  }
}

TEST_F(DwtoolApps, CombineDecoupleAndDeformWriteTheirOutputs) {
  const fs::path other = dir / "other.png";
  imageio::write_image(other.string(), testimages::generate(testimages::Pattern::Edges, 40, 50, 1, 8));
  Result r = dwtool(dir, "combine -i " + quoted(input) + " --detail " + quoted(other) + " -o " + quoted(dir / "c.png") +
                             " --levels 3 --fit tile");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("tiled"), std::string::npos) << r.err;
  r = dwtool(dir, "decouple -i " + quoted(input) + " -o " + quoted(dir / "decal.png") + " --illuminance " +
                      quoted(dir / "light.png") + " --levels 3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "decal.png") && fs::exists(dir / "light.png"));
  r = dwtool(dir, "deform --head -o " + quoted(dir / "head.ply") + " --mesh " + quoted(dir / "head.obj") +
                      " --picture " + quoted(dir / "head.png") + " --band '2:*=1.5' --subdivisions 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(wavelet_apps::read_control_net(dir / "head.ply").columns, 48);
  EXPECT_TRUE(fs::exists(dir / "head.obj") && fs::exists(dir / "head.png"));
}

TEST_F(DwtoolApps, BadInputGivesOneLineExitOneAndNoOutput) {
  const fs::path out = dir / "out.png";
  const std::string edit = "edit -i " + quoted(input) + " -o " + quoted(out) + " --levels 4 ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {edit + "--band Q:1:HH=2", "unknown channel 'Q'"},
      {edit + "--band 1:XY=2", "unknown orientation 'XY'"},
      {edit + "--band 5:HH=2", "level 5 exceeds the 4"},
      {edit + "--band 1:HH=abc", "'abc' is not a number"},
      {edit + "--space lab", "unknown colour space"},
      {"edit -i " + quoted(input) + " -o " + quoted(out) + " --levels 9", "levels"},
      {"edit -i " + quoted(dir / "missing.png") + " -o " + quoted(out), "missing.png"},
      {"combine -i " + quoted(input) + " --detail " + quoted(dir / "missing.png") + " -o " + quoted(out),
       "missing.png"},
      {"combine -i " + quoted(input) + " --detail " + quoted(input) + " -o " + quoted(out) + " --band Y:1:*=bigger",
       "unknown rule"},
      {"decouple -i " + quoted(input) + " -o " + quoted(out) + " --illuminance " + quoted(dir / "l.png") +
           " --levels 0",
       "at least one decomposition level"},
      {"deform --head -o " + quoted(dir / "out.ply") + " --levels 9", "levels"},
      {"deform -i " + quoted(input) + " -o " + quoted(dir / "out.ply"), "controlnet"},
  };
  for (const auto& [args, expected] : cases) {
    const Result r = dwtool(dir, args);
    EXPECT_EQ(r.exit_code, 1) << args;
    EXPECT_EQ(r.err.rfind("dwtool: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << args << " -> " << r.err;
    EXPECT_FALSE(fs::exists(out)) << args;
    EXPECT_FALSE(fs::exists(dir / "out.ply")) << args;
    EXPECT_FALSE(fs::exists(dir / "l.png")) << args;
  }
}

}  // namespace
