// Tests for the `performer` command-line tool, run as a subprocess: `info` on a small file and on
// the CMU captures, and the failure contract (non-zero exit, exactly one "performer: " line).

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#ifndef PERFORMER_PATH
#error "PERFORMER_PATH must name the performer binary (see tests/CMakeLists.txt)"
#endif

extern char** environ;

namespace fs = std::filesystem;

namespace {

struct RunResult {
  int exit_code = -1;  // -1 also when the tool died from a signal
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs performer with stdout and stderr sent to files (no pipes, so no deadlock on large output).
RunResult run_performer(const std::vector<std::string>& args) {
  const fs::path dir = fs::temp_directory_path() / ("performer_cli_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string out_path = (dir / "out.txt").string(), err_path = (dir / "err.txt").string();
  std::vector<std::string> all{PERFORMER_PATH};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  RunResult r;
  if (posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ) == 0) {
    int status = 0;
    if (waitpid(pid, &status, 0) == pid && WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  }
  posix_spawn_file_actions_destroy(&actions);
  r.out = slurp(out_path);
  r.err = slurp(err_path);
  fs::remove_all(dir);
  return r;
}

void expect_one_error_line(const RunResult& r) {
  EXPECT_EQ(r.err.rfind("performer: ", 0), 0u) << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.back(), '\n');
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "exactly one line: " << r.err;
}

class TempFile {
 public:
  TempFile(const std::string& name, const std::string& content)
      : path_(fs::temp_directory_path() / (std::to_string(::getpid()) + "_" + name)) {
    std::ofstream(path_, std::ios::binary) << content;
  }
  ~TempFile() { fs::remove(path_); }
  std::string str() const { return path_.string(); }

 private:
  fs::path path_;
};

const char* kSmall =
    "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation "
    "Xrotation\n"
    "  JOINT Spine\n  {\n    OFFSET 0 5 0\n    CHANNELS 3 Zrotation Xrotation Yrotation\n"
    "    End Site\n    {\n      OFFSET 0 3 0\n    }\n  }\n}\n"
    "MOTION\nFrames: 2\nFrame Time: 0.5\n1 2 3 10 20 30 40 50 60\n4 5 6 11 21 31 41 51 61\n";

TEST(PerformerCli, InfoOnASmallFile) {
  const TempFile f("small.bvh", kSmall);
  const RunResult r = run_performer({"info", "--bvh", f.str()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  for (const char* want :
       {"joints: 2 (plus 1 end sites)", "Hips", "Xposition Yposition Zposition Zrotation Yrotation Xrotation", "Spine",
        "Zrotation Xrotation Yrotation", "Spine_end", "channels: 9", "frames: 2", "frame time: 0.5 s",
        "duration: 1.000 s"})
    EXPECT_NE(r.out.find(want), std::string::npos) << "missing '" << want << "' in:\n" << r.out;
}

TEST(PerformerCli, InfoOnCmuCapture) {
  const char* root = std::getenv("GPUJ2K_SOURCE_DIR");
  if (root == nullptr) GTEST_SKIP() << "GPUJ2K_SOURCE_DIR is not set (run through ctest); skipping the CMU test";
  const fs::path path = fs::path(root) / ".." / "shared" / "assets" / "bvh" / "cmu_131_01.bvh";
  if (!fs::exists(path)) GTEST_SKIP() << "motion capture asset " << path << " not found; skipping";
  const RunResult r = run_performer({"info", "--bvh", path.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* want : {"joints: 31 (plus 7 end sites)", "channels: 96", "frames: 994", "frame time: 0.0083333 s"})
    EXPECT_NE(r.out.find(want), std::string::npos) << "missing '" << want << "' in:\n" << r.out;
}

TEST(PerformerCli, MalformedFileIsOneLineWithTheLine) {
  std::string bad = kSmall;
  bad.replace(bad.find("Xrotation Yrotation\n"), 9, "Qrotation");  // Spine's channels, line 9
  const TempFile f("bad.bvh", bad);
  const RunResult r = run_performer({"info", "--bvh", f.str()});
  EXPECT_EQ(r.exit_code, 1);
  expect_one_error_line(r);
  EXPECT_NE(r.err.find("bad.bvh:9: unknown channel 'Qrotation'"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST(PerformerCli, UsageErrors) {
  for (const auto& args : std::vector<std::vector<std::string>>{
           {}, {"info"}, {"info", "--bvh"}, {"dance"}, {"info", "--bvh", "a.bvh", "--bogus"}}) {
    const RunResult r = run_performer(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    expect_one_error_line(r);
  }
  const RunResult missing = run_performer({"info", "--bvh", "/nonexistent/walk.bvh"});
  EXPECT_EQ(missing.exit_code, 1);
  expect_one_error_line(missing);
  EXPECT_NE(missing.err.find("/nonexistent/walk.bvh: cannot open file"), std::string::npos) << missing.err;
}

}  // namespace
