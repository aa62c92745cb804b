// Tests for the `performer` command-line tool, run as a subprocess: `info` on a small file and on
// the CMU captures, and the failure contract (non-zero exit, exactly one "performer: " line).

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <cstdint>
#include <string>
#include <vector>

#include "imageio/image.h"
#include "imageio/read.h"

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

#ifndef PERFORMER_SPEAKS
#error "PERFORMER_SPEAKS must say whether the performer was built with speech (see tests/CMakeLists.txt)"
#endif
// Whether the performer can speak text (GPUJ2K_PERFORMER_SPEECH); without it `--text` is refused.
constexpr bool kPerformerSpeaks = PERFORMER_SPEAKS;
constexpr const char* kNoSpeech = "speech was not built (GPUJ2K_PERFORMER_SPEECH=OFF); this test speaks text";

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

// A scratch folder for one test, removed at the end.
class ScratchFolder {
 public:
  explicit ScratchFolder(const std::string& name)
      : path_(fs::temp_directory_path() / (std::to_string(::getpid()) + "_" + name)) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchFolder() { fs::remove_all(path_); }
  fs::path operator/(const std::string& leaf) const { return path_ / leaf; }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::size_t count_lines(const std::string& text) {
  std::size_t n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

// Text to weights to faces: Cantonese 你好 through espeak-ng gives a WAV and a CSV whose first frame
// shows the n of 你 (viseme N); `face` then writes one PLY per frame of that CSV, each with the
// procedural head's vertex count in its header.
TEST(PerformerCli, VisemesThenFace) {
  if (!kPerformerSpeaks) GTEST_SKIP() << kNoSpeech;
  const ScratchFolder dir("visemes_face");
  const RunResult v = run_performer({"visemes", "--lang", "yue", "--text", "你好", "--fps", "25", "-o",
                                     (dir / "w.csv").string(), "--wav", (dir / "hello.wav").string(), "--no-blink"});
  ASSERT_EQ(v.exit_code, 0) << v.err;
  const std::string csv = slurp(dir / "w.csv");
  ASSERT_EQ(csv.rfind("time,closed,IY,EH,AA,O,UH,Y,L,M,N,NG,F,TH,S,SH,K\n", 0), 0u) << csv;
  EXPECT_EQ(csv.find("\n0,0,0,0,0,0,0,0,0,0,1,"), csv.find('\n')) << "frame 0 is all N (the n of nei5): " << csv;
  const std::size_t frames = count_lines(csv) - 1;
  EXPECT_GE(frames, 8u) << "about 0.45 s of speech at 25 fps";
  EXPECT_GT(fs::file_size(dir / "hello.wav"), 44u + 2u * 22050u / 4u) << "over a quarter second of 22050 Hz audio";

  const RunResult f = run_performer({"face", "--weights", (dir / "w.csv").string(), "-o", (dir / "frames").string()});
  ASSERT_EQ(f.exit_code, 0) << f.err;
  std::size_t written = 0;
  for (const auto& e : fs::directory_iterator(dir / "frames")) written += e.path().extension() == ".ply";
  EXPECT_EQ(written, frames);
  const std::string ply = slurp(dir / "frames" / "frame_00000.ply");
  EXPECT_NE(ply.find("element vertex 9298\n"), std::string::npos) << ply.substr(0, 200);

  const RunResult obj =
      run_performer({"face", "--weights", (dir / "w.csv").string(), "-o", (dir / "objs").string(), "--format", "obj"});
  ASSERT_EQ(obj.exit_code, 0) << obj.err;
  EXPECT_TRUE(fs::exists(dir / "objs" / "frame_00000.obj"));
}

// Bad lip-sync input: one line, exit 1, and no output file left behind.
TEST(PerformerCli, VisemesAndFaceBadInput) {
  const ScratchFolder dir("visemes_bad");
  const std::string out = (dir / "w.csv").string();
  if (kPerformerSpeaks) {
    const RunResult lang = run_performer({"visemes", "--lang", "xx", "--text", "hi", "-o", out});
    EXPECT_EQ(lang.exit_code, 1);
    expect_one_error_line(lang);
    EXPECT_NE(lang.err.find("'xx'"), std::string::npos) << lang.err;
    EXPECT_FALSE(fs::exists(out));

    const RunResult hanzi = run_performer({"visemes", "--lang", "cmn-latn-pinyin", "--text", "你好", "-o", out});
    EXPECT_EQ(hanzi.exit_code, 1);
    expect_one_error_line(hanzi);
    EXPECT_FALSE(fs::exists(out));
  }

  const RunResult two = run_performer({"visemes", "--lang", "en-us", "--text", "hi", "--rhubarb", "x.tsv", "-o", out});
  EXPECT_EQ(two.exit_code, 1);
  expect_one_error_line(two);

  const TempFile keys("keys.txt", "0 0.2 n yue onset\n0.2 zero ei yue nucleus\n");
  const RunResult k = run_performer({"visemes", "--keyframes", keys.str(), "-o", out});
  EXPECT_EQ(k.exit_code, 1);
  expect_one_error_line(k);
  EXPECT_NE(k.err.find("keys.txt:2:"), std::string::npos) << k.err;
  EXPECT_FALSE(fs::exists(out));

  const TempFile weights("w.csv", "time,AA\n0,1\n0.04,banana\n");
  const RunResult f = run_performer({"face", "--weights", weights.str(), "-o", (dir / "frames").string()});
  EXPECT_EQ(f.exit_code, 1);
  expect_one_error_line(f);
  EXPECT_NE(f.err.find("w.csv:3:"), std::string::npos) << f.err;

  const TempFile good("good.csv", "time,AA\n0,1\n");
  const RunResult gltf = run_performer(
      {"face", "--weights", good.str(), "--gltf", "/nonexistent/avatar.glb", "-o", (dir / "frames").string()});
  EXPECT_EQ(gltf.exit_code, 1);
  expect_one_error_line(gltf);
  EXPECT_NE(gltf.err.find("/nonexistent/avatar.glb"), std::string::npos) << gltf.err;
}

// Built without speech, `--text` is one line saying so, and nothing is written; lip sync from a
// weight track still drives the face.
TEST(PerformerCli, TextWithoutSpeechIsOneLineAndNoOutput) {
  if (kPerformerSpeaks) GTEST_SKIP() << "speech is built; this checks the performer built without it";
  const ScratchFolder dir("no_speech");
  const RunResult v = run_performer({"visemes", "--lang", "en-us", "--text", "hi", "-o", (dir / "w.csv").string(),
                                     "--wav", (dir / "hi.wav").string()});
  EXPECT_EQ(v.exit_code, 1);
  expect_one_error_line(v);
  EXPECT_NE(v.err.find("speech was not built"), std::string::npos) << v.err;
  EXPECT_TRUE(fs::is_empty(dir.path())) << "no weights, no WAV, no temporary";

  const TempFile weights("w.csv", "time,AA\n0,1\n0.04,0.5\n");
  const RunResult f = run_performer({"face", "--weights", weights.str(), "-o", (dir / "frames").string()});
  ASSERT_EQ(f.exit_code, 0) << f.err;
  EXPECT_TRUE(fs::exists(dir / "frames" / "frame_00000.ply"));
  EXPECT_TRUE(fs::exists(dir / "frames" / "frame_00001.ply"));
}

// The whole performer from the command line: speech drives the face while a CMU capture drives
// the body; one mesh per BVH frame. Bad frame ranges are one line and write nothing.
TEST(PerformerCli, PoseWithSpeech) {
  if (!kPerformerSpeaks) GTEST_SKIP() << kNoSpeech;
  const char* root = std::getenv("GPUJ2K_SOURCE_DIR");
  if (root == nullptr) GTEST_SKIP() << "GPUJ2K_SOURCE_DIR is not set (run through ctest); skipping the CMU test";
  const fs::path bvh = fs::path(root) / ".." / "shared" / "assets" / "bvh" / "cmu_131_01.bvh";
  if (!fs::exists(bvh)) GTEST_SKIP() << "motion capture asset " << bvh << " not found; skipping";
  const ScratchFolder dir("pose");
  const RunResult r = run_performer({"pose", "--bvh", bvh.string(), "--frames", "200:202", "--lang", "en-us", "--text",
                                     "Hello", "-o", (dir / "frames").string(), "--format", "obj"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* name : {"frame_00200.obj", "frame_00201.obj", "frame_00202.obj"})
    EXPECT_TRUE(fs::exists(dir / "frames" / name)) << name;
  EXPECT_FALSE(fs::exists(dir / "frames" / "frame_00203.obj"));
  const std::string obj = slurp(dir / "frames" / "frame_00200.obj");
  std::size_t vertices = 0;
  for (std::size_t at = obj.find("\nv "); at != std::string::npos; at = obj.find("\nv ", at + 1)) ++vertices;
  EXPECT_GT(vertices, 15000u) << "body and head";

  for (const char* range : {"5:2", "x:3", "990:999"}) {
    const RunResult bad =
        run_performer({"pose", "--bvh", bvh.string(), "--frames", range, "-o", (dir / "bad").string()});
    EXPECT_EQ(bad.exit_code, 1) << range;
    expect_one_error_line(bad);
    EXPECT_FALSE(fs::exists(dir / "bad")) << range;
  }
}

// `performer render` end to end: an MP4 that ffprobe reads with the size and frame count asked for
// and an audio stream as long as the speech (within one frame).
std::string run_ffprobe(const fs::path& video, const std::string& entries, const std::string& stream) {
  const ScratchFolder dir("ffprobe");
  const std::string out = (dir / "probe.txt").string();
  const std::string command = "ffprobe -v error -select_streams " + stream + " -show_entries stream=" + entries +
                              " -of default=noprint_wrappers=1:nokey=1 '" + video.string() + "' > '" + out + "'";
  if (std::system(command.c_str()) != 0) return {};
  return slurp(out);
}

double wav_seconds(const fs::path& wav) {
  const std::string bytes = slurp(wav);
  if (bytes.size() < 44) return 0.0;
  auto u32 = [&](std::size_t at) {
    return static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[at])) |
           static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[at + 1])) << 8 |
           static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[at + 2])) << 16 |
           static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[at + 3])) << 24;
  };
  const std::uint32_t rate = u32(24);
  const std::size_t data = bytes.find("data");
  if (rate == 0 || data == std::string::npos) return 0.0;
  return static_cast<double>(u32(data + 4)) / 2.0 / rate;  // 16-bit mono
}

TEST(PerformerCli, RenderWritesVideoWithTheSpeech) {
  if (!kPerformerSpeaks) GTEST_SKIP() << kNoSpeech;
  const char* root = std::getenv("GPUJ2K_SOURCE_DIR");
  if (root == nullptr) GTEST_SKIP() << "GPUJ2K_SOURCE_DIR is not set (run through ctest); skipping the CMU test";
  const fs::path bvh = fs::path(root) / ".." / "shared" / "assets" / "bvh" / "cmu_131_01.bvh";
  if (!fs::exists(bvh)) GTEST_SKIP() << "motion capture asset " << bvh << " not found; skipping";
  if (std::system("ffprobe -version > /dev/null 2>&1") != 0) GTEST_SKIP() << "ffprobe (Debian: ffmpeg) not installed";
  const ScratchFolder dir("render");
  const std::string text = "Hello there";
  const RunResult r = run_performer({"render", "--bvh", bvh.string(), "--frames", "0:90", "--size", "160x120", "--lang",
                                     "en-us", "--text", text, "--effects", "env,hair,snow,toon", "--cubemap",
                                     (fs::path(root) / ".." / "shared" / "assets" / "cubemap").string(), "-o",
                                     (dir / "hello.mp4").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(dir / "hello.mp4"));
  EXPECT_FALSE(fs::exists(dir / "hello.mp4.partial"));
  // The frame count the command reports: 0.75 s of the clip at 30 fps.
  const std::size_t at = r.err.find(" frames written to ");
  ASSERT_NE(at, std::string::npos) << r.err;
  const int frames = std::stoi(r.err.substr(r.err.rfind(' ', at - 1) + 1));
  EXPECT_GE(frames, 22);
  EXPECT_LE(frames, 23);
  EXPECT_EQ(run_ffprobe(dir / "hello.mp4", "codec_name,width,height,nb_frames", "v:0"),
            "h264\n160\n120\n" + std::to_string(frames) + "\n");
  const std::string audio = run_ffprobe(dir / "hello.mp4", "codec_name,duration", "a:0");
  ASSERT_EQ(audio.rfind("aac\n", 0), 0u) << audio;
  // The same speech, spoken again to a WAV: the video's sound lasts as long, within one frame.
  const RunResult wav = run_performer({"visemes", "--lang", "en-us", "--text", text, "--wav",
                                       (dir / "hello.wav").string(), "-o", (dir / "w.csv").string()});
  ASSERT_EQ(wav.exit_code, 0) << wav.err;
  const double speech = wav_seconds(dir / "hello.wav");
  EXPECT_GT(speech, 0.3);
  EXPECT_NEAR(std::stod(audio.substr(4)), speech, 1.0 / 30.0);
}

TEST(PerformerCli, RenderBadInputIsOneLineAndNoOutput) {
  const char* root = std::getenv("GPUJ2K_SOURCE_DIR");
  if (root == nullptr) GTEST_SKIP() << "GPUJ2K_SOURCE_DIR is not set (run through ctest); skipping the CMU test";
  const fs::path bvh = fs::path(root) / ".." / "shared" / "assets" / "bvh" / "cmu_131_01.bvh";
  if (!fs::exists(bvh)) GTEST_SKIP() << "motion capture asset " << bvh << " not found; skipping";
  const ScratchFolder dir("render_bad");
  const std::string out = (dir / "out.mp4").string();
  const std::vector<std::vector<std::string>> cases = {
      {"render", "--bvh", (dir / "missing.bvh").string(), "-o", out},
      {"render", "--bvh", bvh.string(), "--frames", "990:999", "-o", out},
      {"render", "--bvh", bvh.string(), "--frames", "0:2", "--effects", "fog", "-o", out},
      {"render", "--bvh", bvh.string(), "--frames", "0:2", "--size", "161x120", "-o", out},
      {"render", "--bvh", bvh.string(), "--frames", "0:2", "-o", (dir / "no" / "such" / "dir" / "out.mp4").string()},
      {"render", "--bvh", bvh.string(), "--frames", "0:2", "-o", (dir / "out.gif").string()},
  };
  for (const auto& args : cases) {
    const RunResult bad = run_performer(args);
    EXPECT_EQ(bad.exit_code, 1) << args[2] << " " << bad.err;
    expect_one_error_line(bad);
  }
  EXPECT_TRUE(fs::is_empty(dir.path())) << "no output file, no temporary";
}

// `performer render --gltf`: an avatar made by our own code (`performer avatar`: the generated
// performer as a skinned glTF with morph targets) goes through the same deformer and renderer. The
// video is what ffprobe expects, and a rendered frame of the avatar is the generated performer's
// frame: the avatar is that performer in metres, its joints following the clip by name, and the
// camera frames the figure whatever its units.
fs::path cmu_bvh_or_empty() {
  const char* root = std::getenv("GPUJ2K_SOURCE_DIR");
  if (root == nullptr) return {};
  const fs::path bvh = fs::path(root) / ".." / "shared" / "assets" / "bvh" / "cmu_131_01.bvh";
  return fs::exists(bvh) ? bvh : fs::path();
}

TEST(PerformerCli, RenderGltfAvatarWritesVideoAndShowsTheAvatar) {
  const fs::path bvh = cmu_bvh_or_empty();
  if (bvh.empty()) GTEST_SKIP() << "GPUJ2K_SOURCE_DIR unset or ../shared/assets/bvh/cmu_131_01.bvh absent; skipping";
  if (std::system("ffprobe -version > /dev/null 2>&1") != 0) GTEST_SKIP() << "ffprobe (Debian: ffmpeg) not installed";
  const ScratchFolder dir("render_gltf");
  const std::string avatar = (dir / "generated.glb").string();
  const RunResult made = run_performer({"avatar", "--bvh", bvh.string(), "-o", avatar});
  ASSERT_EQ(made.exit_code, 0) << made.err;
  ASSERT_TRUE(fs::exists(avatar));

  // With speech when it is built; the video is checked the same either way.
  std::vector<std::string> video_args = {"render",
                                         "--gltf",
                                         avatar,
                                         "--bvh",
                                         bvh.string(),
                                         "--frames",
                                         "0:9",
                                         "--size",
                                         "160x120",
                                         "-o",
                                         (dir / "out.mp4").string()};
  if (kPerformerSpeaks) video_args.insert(video_args.end(), {"--lang", "en-us", "--text", "Hi"});
  const RunResult r = run_performer(video_args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("38 of 38 joints follow the clip by name"), std::string::npos) << r.err;
  const std::size_t at = r.err.find(" frames written to ");
  ASSERT_NE(at, std::string::npos) << r.err;
  const int frames = std::stoi(r.err.substr(r.err.rfind(' ', at - 1) + 1));
  EXPECT_EQ(frames, 3);  // 9 frames of a 120 fps clip at 30 fps
  EXPECT_EQ(run_ffprobe(dir / "out.mp4", "codec_name,width,height,nb_frames", "v:0"),
            "h264\n160\n120\n" + std::to_string(frames) + "\n");

  // One frame as PNG, of the avatar and of the generated performer.
  for (const char* which : {"avatar_frames", "generated_frames"}) {
    std::vector<std::string> args = {"render",  "--bvh", bvh.string(),          "--frames", "300:300", "--size",
                                     "160x120", "-o",    (dir / which).string()};
    if (std::string(which) == "avatar_frames") args.insert(args.end(), {"--gltf", avatar});
    const RunResult png = run_performer(args);
    ASSERT_EQ(png.exit_code, 0) << png.err;
  }
  const imageio::Image a = imageio::read_image((dir / "avatar_frames" / "frame_00000.png").string());
  const imageio::Image g = imageio::read_image((dir / "generated_frames" / "frame_00000.png").string());
  ASSERT_EQ(a.width, 160);
  ASSERT_EQ(a.height, 120);
  ASSERT_EQ(a.pixels.size(), g.pixels.size());
  const float full = static_cast<float>((1 << a.bits_per_sample) - 1);
  // The figure's cloth is a bluer blue than the sky's: more blue over red than anywhere in the
  // frame's left and right fifths, which the figure, framed in the middle, leaves to sky and floor.
  auto blueness = [&](int x, int y) { return (a.at(x, y, 2) - a.at(x, y, 0)) / full; };
  float background = 0.0f;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      if (x < a.width / 5 || x >= a.width - a.width / 5) background = std::max(background, blueness(x, y));
  std::size_t differ = 0, figure = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      float d = 0.0f;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(a.at(x, y, c) - g.at(x, y, c)) / full);
      differ += d > 0.1f;
      figure += blueness(x, y) > background + 0.04f;
    }
  const std::size_t pixels = static_cast<std::size_t>(a.width * a.height);
  std::printf("avatar frame: %zu of %zu pixels differ from the generated performer's, %zu show the cloth\n", differ,
              pixels, figure);
  EXPECT_LT(differ, pixels / 100);
  EXPECT_GT(figure, pixels / 200);
}

// A minimal glTF (one triangle, embedded buffer) with neither a skin nor morph targets.
const char* kBareGltf =
    R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)"
    R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],"bufferViews":[{"buffer":0,"byteLength":36}],)"
    R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],)"
    R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})";

// The same triangle skinned to one joint, "Tail", which no motion capture skeleton has.
const char* kTailGltf =
    R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":108,"uri":"data:application/octet-stream;base64,)"
    R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8A)"
    R"(AAAAAAAAAAAAAAAAAIA/AAAAAAAAAAAAAAAA"}],"bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,)"
    R"("byteOffset":36,"byteLength":24},{"buffer":0,"byteOffset":60,"byteLength":48}],"accessors":[{"bufferView":0,)"
    R"("componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},{"bufferView":1,"componentType":5123,)"
    R"("count":3,"type":"VEC4"},{"bufferView":2,"componentType":5126,"count":3,"type":"VEC4"}],"meshes":[{"primitives":)"
    R"([{"attributes":{"POSITION":0,"JOINTS_0":1,"WEIGHTS_0":2}}]}],"skins":[{"joints":[1]}],"nodes":[{"mesh":0,)"
    R"("skin":0},{"name":"Tail"}],"scenes":[{"nodes":[0,1]}]})";

TEST(PerformerCli, RenderGltfBadInputIsOneLineAndNoOutput) {
  const fs::path bvh = cmu_bvh_or_empty();
  if (bvh.empty()) GTEST_SKIP() << "GPUJ2K_SOURCE_DIR unset or ../shared/assets/bvh/cmu_131_01.bvh absent; skipping";
  const ScratchFolder inputs("render_gltf_inputs");
  std::ofstream(inputs / "corrupt.glb", std::ios::binary) << "glTF (magic bytes), then not a binary glTF at all";
  std::ofstream(inputs / "bare.gltf") << kBareGltf;
  std::ofstream(inputs / "tail.gltf") << kTailGltf;
  const ScratchFolder dir("render_gltf_bad");
  const std::string out = (dir / "out.mp4").string();
  const struct {
    fs::path avatar;
    const char* says;
  } cases[] = {
      {inputs / "missing.glb", "cannot open file"},
      {inputs / "corrupt.glb", "not a readable glTF 2.0 file"},
      {inputs / "bare.gltf", "no skinned mesh and no morph targets"},
      {inputs / "tail.gltf", "none of the avatar's joints (Tail)"},
  };
  for (const auto& c : cases) {
    const RunResult bad =
        run_performer({"render", "--bvh", bvh.string(), "--frames", "0:2", "--gltf", c.avatar.string(), "-o", out});
    EXPECT_EQ(bad.exit_code, 1) << c.avatar << " " << bad.err;
    expect_one_error_line(bad);
    EXPECT_NE(bad.err.find(c.avatar.string()), std::string::npos) << "names the file: " << bad.err;
    EXPECT_NE(bad.err.find(c.says), std::string::npos) << bad.err;
  }
  EXPECT_TRUE(fs::is_empty(dir.path())) << "no output file, no temporary";
  const RunResult wrong = run_performer({"avatar", "--bvh", bvh.string(), "-o", (dir / "avatar.obj").string()});
  EXPECT_EQ(wrong.exit_code, 1) << wrong.err;
  expect_one_error_line(wrong);
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

}  // namespace
