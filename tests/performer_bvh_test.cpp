// Tests for the BVH reader: the CMU motion capture files the performer ships with, the layout
// variations real files show (line ends, blanks, letter case, channel orders and counts, several
// roots), and one malformed text per kind of error, checking the line the error names.

#include <gtest/gtest.h>

#include "support/shared_assets.h"

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "performer/bvh.h"
#include "performer/skeleton.h"

namespace fs = std::filesystem;
using performer::BvhError;
using performer::Channel;
using performer::parse_bvh;

namespace {

using test_support::bvh_asset;
#define REQUIRE_BVH_ASSET(path) REQUIRE_SHARED_FILE(path)

struct CmuFile {
  const char* name;
  int frames;
  float first_values[3];  // root Xposition Yposition Zposition of the first row
  float last_value;       // last value of the last row
};

const CmuFile kCmuFiles[] = {
    {"cmu_131_01.bvh", 994, {5.2300f, 16.9002f, -33.8986f}, 19.734f},
    {"cmu_131_02.bvh", 1247, {4.8105f, 17.0973f, -20.3817f}, 40.2663f},
    {"cmu_131_03.bvh", 1102, {5.1723f, 16.9371f, -29.1264f}, 13.7094f},
};

// Joints (end sites excluded) in file order, read off cmu_131_01.bvh; the three files share them.
const std::vector<std::string> kCmuJoints = {
    "Hips",        "LHipJoint",     "LeftHip",      "LeftKnee",   "LeftAnkle", "LeftToe",  "RHipJoint", "RightHip",
    "RightKnee",   "RightAnkle",    "RightToe",     "lowerback",  "Chest",     "Chest2",   "lowerneck", "Neck",
    "Head",        "LeftCollar",    "LeftShoulder", "LeftElbow",  "LeftWrist", "lhand",    "LFingers",  "LThumb",
    "RightCollar", "RightShoulder", "RightElbow",   "RightWrist", "rhand",     "RFingers", "RThumb"};

// The arm joints below the collars are written Z X Y in these files; everything else Z Y X.
bool cmu_arm_joint(const std::string& name) {
  for (const char* arm : {"LeftShoulder", "LeftElbow", "LeftWrist", "lhand", "LFingers", "LThumb", "RightShoulder",
                          "RightElbow", "RightWrist", "rhand", "RFingers", "RThumb"})
    if (name == arm) return true;
  return false;
}

class CmuBvh : public ::testing::TestWithParam<CmuFile> {};

TEST_P(CmuBvh, ParsesSkeletonAndMotion) {
  const CmuFile& f = GetParam();
  const fs::path path = bvh_asset(f.name);
  REQUIRE_BVH_ASSET(path);
  const performer::Bvh bvh = performer::read_bvh(path);
  const performer::Skeleton& sk = bvh.skeleton;

  EXPECT_EQ(performer::animated_joint_count(sk), 31);
  std::vector<std::string> names;
  for (const auto& j : sk.joints)
    if (!j.end_site) names.push_back(j.name);
  EXPECT_EQ(names, kCmuJoints);
  EXPECT_EQ(sk.joints.size(), 38u) << "31 joints and 7 end sites";

  const std::vector<Channel> root_order{Channel::Xposition, Channel::Yposition, Channel::Zposition,
                                        Channel::Zrotation, Channel::Yrotation, Channel::Xrotation};
  const std::vector<Channel> zyx{Channel::Zrotation, Channel::Yrotation, Channel::Xrotation};
  const std::vector<Channel> zxy{Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
  ASSERT_EQ(sk.joints[0].name, "Hips");
  EXPECT_EQ(sk.joints[0].parent, -1);
  EXPECT_EQ(sk.joints[0].channels, root_order);
  int expected_offset = 0;
  for (std::size_t i = 0; i < sk.joints.size(); ++i) {
    const performer::Joint& j = sk.joints[i];
    EXPECT_LT(j.parent, static_cast<int>(i)) << "parents precede children";
    EXPECT_EQ(j.channel_offset, expected_offset) << j.name;
    expected_offset += static_cast<int>(j.channels.size());
    if (i == 0) continue;
    EXPECT_GE(j.parent, 0) << j.name;
    if (j.end_site)
      EXPECT_TRUE(j.channels.empty()) << j.name;
    else
      EXPECT_EQ(j.channels, cmu_arm_joint(j.name) ? zxy : zyx) << j.name;
  }
  EXPECT_EQ(performer::channel_count(sk), 96);

  // Spot checks of the hierarchy and offsets against the text.
  const int left_hip = performer::find_joint(sk, "LeftHip");
  ASSERT_GE(left_hip, 0);
  EXPECT_EQ(sk.joints[static_cast<std::size_t>(left_hip)].parent, performer::find_joint(sk, "LHipJoint"));
  EXPECT_EQ(sk.joints[static_cast<std::size_t>(performer::find_joint(sk, "LThumb"))].parent,
            performer::find_joint(sk, "LeftWrist"));
  EXPECT_EQ(sk.joints[static_cast<std::size_t>(performer::find_joint(sk, "Head_end"))].parent,
            performer::find_joint(sk, "Head"));

  const performer::Motion& m = bvh.motion;
  EXPECT_EQ(m.frames, f.frames);
  EXPECT_DOUBLE_EQ(m.frame_time, 0.0083333);
  ASSERT_EQ(m.values.size(), static_cast<std::size_t>(f.frames) * 96u);
  EXPECT_FLOAT_EQ(m.values[0], f.first_values[0]);
  EXPECT_FLOAT_EQ(m.values[1], f.first_values[1]);
  EXPECT_FLOAT_EQ(m.values[2], f.first_values[2]);
  EXPECT_FLOAT_EQ(m.values.back(), f.last_value);
}

INSTANTIATE_TEST_SUITE_P(Cmu131, CmuBvh, ::testing::ValuesIn(kCmuFiles),
                         [](const auto& info) { return std::string(info.param.name).substr(8, 2); });

TEST(CmuBvh, OffsetsMatchTheText) {
  const fs::path path = bvh_asset("cmu_131_01.bvh");
  REQUIRE_BVH_ASSET(path);
  const performer::Skeleton sk = performer::read_bvh(path).skeleton;
  const auto& knee = sk.joints[static_cast<std::size_t>(performer::find_joint(sk, "LeftKnee"))];
  EXPECT_FLOAT_EQ(knee.offset.x, 2.49329f);
  EXPECT_FLOAT_EQ(knee.offset.y, -6.85026f);
  EXPECT_FLOAT_EQ(knee.offset.z, 0.0f);
  const auto& toe_end = sk.joints[static_cast<std::size_t>(performer::find_joint(sk, "LeftToe_end"))];
  EXPECT_TRUE(toe_end.end_site);
  EXPECT_FLOAT_EQ(toe_end.offset.z, 1.13491f);
}

// A small valid file; the error tests below break one line each. Line numbers in comments.
std::vector<std::string> base_lines() {
  return {
      "HIERARCHY",                                                                 // 1
      "ROOT Hips",                                                                 // 2
      "{",                                                                         // 3
      "  OFFSET 0 0 0",                                                            // 4
      "  CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation",  // 5
      "  JOINT Spine",                                                             // 6
      "  {",                                                                       // 7
      "    OFFSET 0 5 0",                                                          // 8
      "    CHANNELS 3 Zrotation Xrotation Yrotation",                              // 9
      "    End Site",                                                              // 10
      "    {",                                                                     // 11
      "      OFFSET 0 3 0",                                                        // 12
      "    }",                                                                     // 13
      "  }",                                                                       // 14
      "}",                                                                         // 15
      "MOTION",                                                                    // 16
      "Frames: 2",                                                                 // 17
      "Frame Time: 0.5",                                                           // 18
      "1 2 3 10 20 30 40 50 60",                                                   // 19
      "4 5 6 11 21 31 41 51 61",                                                   // 20
  };
}

std::string join(const std::vector<std::string>& lines, const std::string& eol = "\n") {
  std::string text;
  for (const auto& l : lines) text += l + eol;
  return text;
}

TEST(BvhParse, SmallFile) {
  const performer::Bvh bvh = parse_bvh(join(base_lines()), "small.bvh");
  const auto& sk = bvh.skeleton;
  ASSERT_EQ(sk.joints.size(), 3u);
  EXPECT_EQ(sk.joints[1].name, "Spine");
  EXPECT_EQ(sk.joints[1].parent, 0);
  EXPECT_EQ(sk.joints[1].channel_offset, 6);
  EXPECT_EQ(sk.joints[2].name, "Spine_end");
  EXPECT_TRUE(sk.joints[2].end_site);
  EXPECT_EQ(sk.joints[2].channel_offset, 9);
  EXPECT_EQ(sk.joints[1].offset, glm::vec3(0, 5, 0));
  EXPECT_EQ(bvh.motion.frames, 2);
  EXPECT_DOUBLE_EQ(bvh.motion.frame_time, 0.5);
  const std::vector<float> values{1, 2, 3, 10, 20, 30, 40, 50, 60, 4, 5, 6, 11, 21, 31, 41, 51, 61};
  EXPECT_EQ(bvh.motion.values, values);
  const auto row1 = performer::frame_values(sk, bvh.motion, 1);
  EXPECT_EQ(std::vector<float>(row1.begin(), row1.end()), std::vector<float>(values.begin() + 9, values.end()));
  EXPECT_THROW((void)performer::frame_values(sk, bvh.motion, 2), std::out_of_range);
}

// The same file written the ways real files are: CRLF or mixed line ends, tabs, blank lines,
// trailing blanks, a byte order mark, keywords in other cases, glued braces and labels, '+' signs.
TEST(BvhParse, LayoutVariationsGiveTheSameResult) {
  const performer::Bvh clean = parse_bvh(join(base_lines()));
  const std::string messy =
      "\xEF\xBB\xBFHIERARCHY \r\n"
      "\r\n"
      "root Hips{\r\n"
      "\tOFFSET\t0 0   0\t\r\n"
      "\tCHANNELS 6 Xposition Yposition Zposition ZROTATION Yrotation Xrotation   \n"
      "\tJOINT Spine\r"  // a lone CR ends a line too
      "\t{\n"
      "\t\tOFFSET +0 5.0 0e0\r\n"
      "\t\tCHANNELS 3 Zrotation Xrotation Yrotation\r\n"
      "\t\tEnd site\r\n"
      "\t\t{ OFFSET 0 3 0 }\r\n"
      "\t}\r\n"
      "}\r\n"
      "\r\n"
      "Motion\r\n"
      "Frames:2\r\n"
      "Frame Time:\t.5\r\n"
      "\r\n"
      "1 2 3 10 20 30 40 50 60   \r\n"
      "\t4 5 6 11 21 31 41 51 +61\r\n"
      "\r\n\r\n";
  const performer::Bvh messy_bvh = parse_bvh(messy);
  ASSERT_EQ(messy_bvh.skeleton.joints.size(), clean.skeleton.joints.size());
  for (std::size_t i = 0; i < clean.skeleton.joints.size(); ++i) {
    EXPECT_EQ(messy_bvh.skeleton.joints[i].name, clean.skeleton.joints[i].name);
    EXPECT_EQ(messy_bvh.skeleton.joints[i].parent, clean.skeleton.joints[i].parent);
    EXPECT_EQ(messy_bvh.skeleton.joints[i].offset, clean.skeleton.joints[i].offset);
    EXPECT_EQ(messy_bvh.skeleton.joints[i].channels, clean.skeleton.joints[i].channels);
  }
  EXPECT_EQ(messy_bvh.motion.frames, clean.motion.frames);
  EXPECT_EQ(messy_bvh.motion.frame_time, clean.motion.frame_time);
  EXPECT_EQ(messy_bvh.motion.values, clean.motion.values);
  // And plain CRLF throughout.
  EXPECT_EQ(parse_bvh(join(base_lines(), "\r\n")).motion.values, clean.motion.values);
}

TEST(BvhParse, ChannelCountsAndOrdersAndSeveralRoots) {
  const std::string text =
      "HIERARCHY\n"
      "ROOT A\n{\n OFFSET 1 2 3\n CHANNELS 0\n"
      " JOINT B\n {\n  OFFSET 0 1 0\n  CHANNELS 1 Yposition\n"
      "  JOINT C D\n  {\n   OFFSET 0 0 1\n"  // no CHANNELS at all, and a name with a blank
      "   JOINT E\n   {\n    OFFSET 1 0 0\n    CHANNELS 6 Yrotation Xposition Zrotation Zposition Xrotation Yposition\n"
      "    End Site\n    {\n     OFFSET 0 0 0\n    }\n   }\n  }\n }\n}\n"
      "ROOT Prop\n{\n OFFSET 0 0 0\n CHANNELS 2 Xrotation Xposition\n}\n"
      "MOTION\nFrames: 1\nFrame Time: 0.04\n"
      "7  1 2 3 4 5 6  8 9\n";
  const performer::Bvh bvh = parse_bvh(text);
  const auto& j = bvh.skeleton.joints;
  ASSERT_EQ(j.size(), 6u);
  EXPECT_EQ(j[0].name, "A");
  EXPECT_TRUE(j[0].channels.empty());
  EXPECT_EQ(j[0].channel_offset, 0);
  EXPECT_EQ(j[1].channels, std::vector<Channel>{Channel::Yposition});
  EXPECT_EQ(j[1].channel_offset, 0);
  EXPECT_EQ(j[2].name, "C D");
  EXPECT_TRUE(j[2].channels.empty());
  EXPECT_EQ(j[2].channel_offset, 1);
  EXPECT_EQ(j[3].channels, (std::vector<Channel>{Channel::Yrotation, Channel::Xposition, Channel::Zrotation,
                                                 Channel::Zposition, Channel::Xrotation, Channel::Yposition}));
  EXPECT_EQ(j[3].channel_offset, 1);
  EXPECT_TRUE(j[4].end_site);
  EXPECT_EQ(j[4].parent, 3);
  EXPECT_EQ(j[5].name, "Prop");
  EXPECT_EQ(j[5].parent, -1) << "a second ROOT is a second root, not an error";
  EXPECT_EQ(j[5].channel_offset, 7);
  EXPECT_EQ(performer::channel_count(bvh.skeleton), 9);
  EXPECT_EQ(bvh.motion.values, (std::vector<float>{7, 1, 2, 3, 4, 5, 6, 8, 9}));
}

TEST(BvhParse, NoFramesAndNoChannels) {
  const performer::Bvh zero =
      parse_bvh("HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n}\nMOTION\nFrames: 0\nFrame Time: 0.1\n");
  EXPECT_EQ(zero.motion.frames, 0);
  EXPECT_TRUE(zero.motion.values.empty());
  const performer::Bvh still =
      parse_bvh("HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\n}\nMOTION\nFrames: 3\nFrame Time: 0.1\n\n\n\n");
  EXPECT_EQ(still.motion.frames, 3);
  EXPECT_TRUE(still.motion.values.empty());
}

// Parses `lines` and expects a BvhError naming `line`; returns the message for further checks.
std::string expect_error_at(const std::vector<std::string>& lines, int line, const std::string& eol = "\n") {
  try {
    parse_bvh(join(lines, eol), "bad.bvh");
  } catch (const BvhError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.file(), "bad.bvh");
    const std::string prefix = "bad.bvh:" + std::to_string(line) + ": ";
    EXPECT_EQ(std::string(e.what()).substr(0, prefix.size()), prefix) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no BvhError for a text that should fail at line " << line;
  return {};
}

TEST(BvhErrors, TruncatedInTheHierarchy) {
  auto lines = base_lines();
  lines.resize(9);
  const std::string msg = expect_error_at(lines, 9);
  EXPECT_NE(msg.find("end of file"), std::string::npos) << msg;
  // Also with CRLF and trailing blank lines: the last line with content is still 9.
  lines.push_back("");
  lines.push_back("   ");
  expect_error_at(lines, 9, "\r\n");
}

TEST(BvhErrors, TruncatedInTheMotion) {
  auto lines = base_lines();
  lines.resize(19);  // one of two rows
  const std::string msg = expect_error_at(lines, 19);
  EXPECT_NE(msg.find("1 motion rows of the 2 declared"), std::string::npos) << msg;
  lines = base_lines();
  lines.resize(18);  // header only
  expect_error_at(lines, 18);
}

TEST(BvhErrors, TruncatedMidRow) {
  auto lines = base_lines();
  lines[19] = "4 5 6 11";  // the file stops part way through line 20
  const std::string msg = expect_error_at(lines, 20);
  EXPECT_NE(msg.find("has 4 values, expected 9"), std::string::npos) << msg;
}

TEST(BvhErrors, WrongValueCountInARow) {
  auto lines = base_lines();
  lines[18] = "1 2 3 10 20 30 40 50 60 70";  // line 19, one too many
  std::string msg = expect_error_at(lines, 19);
  EXPECT_NE(msg.find("has 10 values, expected 9"), std::string::npos) << msg;
  lines = base_lines();
  lines[19] = "4 5 6 11 21 31 41 51";  // line 20, one too few
  msg = expect_error_at(lines, 20);
  EXPECT_NE(msg.find("has 8 values, expected 9"), std::string::npos) << msg;
}

TEST(BvhErrors, NonNumericValue) {
  for (const char* bad : {"abc", "1.2.3", "4x", "nan", "inf", "--1", "1e999"}) {
    auto lines = base_lines();
    lines[19] = std::string("4 5 6 11 21 31 ") + bad + " 51 61";  // the 7th value: Spine's Zrotation
    const std::string msg = expect_error_at(lines, 20);
    EXPECT_NE(msg.find("non-numeric value"), std::string::npos) << msg;
    EXPECT_NE(msg.find("Zrotation of Spine"), std::string::npos) << "names the channel: " << msg;
  }
  auto lines = base_lines();
  lines[7] = "    OFFSET 0 five 0";
  expect_error_at(lines, 8);
}

TEST(BvhErrors, MissingOpeningBrace) {
  auto lines = base_lines();
  lines.erase(lines.begin() + 6);  // Spine's '{' (line 7); its OFFSET moves up to line 7
  const std::string msg = expect_error_at(lines, 7);
  EXPECT_NE(msg.find("expected '{' after JOINT Spine"), std::string::npos) << msg;
}

TEST(BvhErrors, MissingClosingBrace) {
  auto lines = base_lines();
  lines.erase(lines.begin() + 13);  // Spine's '}' (line 14); MOTION moves up to line 15
  const std::string msg = expect_error_at(lines, 15);
  EXPECT_NE(msg.find("joint Hips (opened on line 3)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'MOTION'"), std::string::npos) << msg;
}

TEST(BvhErrors, UnknownChannel) {
  auto lines = base_lines();
  lines[8] = "    CHANNELS 3 Zrotation Xrotation Wrotation";
  const std::string msg = expect_error_at(lines, 9);
  EXPECT_NE(msg.find("unknown channel 'Wrotation'"), std::string::npos) << msg;
}

TEST(BvhErrors, ChannelListShorterThanItsCount) {
  auto lines = base_lines();
  lines[8] = "    CHANNELS 3 Zrotation Xrotation";
  const std::string msg = expect_error_at(lines, 9);
  EXPECT_NE(msg.find("announces 3 channels but lists 2"), std::string::npos) << msg;
}

TEST(BvhErrors, BadChannelDeclarations) {
  auto lines = base_lines();
  lines[8] = "    CHANNELS 7 Zrotation Xrotation Yrotation Xposition Yposition Zposition Zrotation";
  expect_error_at(lines, 9);
  lines[8] = "    CHANNELS 3 Zrotation Xrotation Zrotation";
  EXPECT_NE(expect_error_at(lines, 9).find("listed twice"), std::string::npos);
  lines = base_lines();
  lines[11] = "      CHANNELS 1 Xrotation";  // inside the End Site
  EXPECT_NE(expect_error_at(lines, 12).find("End Site cannot have CHANNELS"), std::string::npos);
}

TEST(BvhErrors, FrameCount) {
  auto lines = base_lines();
  lines[16] = "Frames: -1";
  EXPECT_NE(expect_error_at(lines, 17).find("negative frame count"), std::string::npos);
  lines[16] = "Frames:";
  EXPECT_NE(expect_error_at(lines, 17).find("missing frame count"), std::string::npos);
  lines[16] = "Frames: two";
  expect_error_at(lines, 17);
  lines[16] = "Frames: 2.5";
  expect_error_at(lines, 17);
  lines.erase(lines.begin() + 16);  // no Frames line at all: "Frame Time:" turns up on line 17
  expect_error_at(lines, 17);
}

TEST(BvhErrors, FrameTime) {
  auto lines = base_lines();
  lines[17] = "Frame Time: 0";
  EXPECT_NE(expect_error_at(lines, 18).find("must be positive"), std::string::npos);
  lines[17] = "Frame Time:";
  expect_error_at(lines, 18);
  lines[17] = "Frame Rate: 0.5";
  expect_error_at(lines, 18);
}

TEST(BvhErrors, MoreRowsThanFrames) {
  auto lines = base_lines();
  lines[16] = "Frames: 1";
  const std::string msg = expect_error_at(lines, 20);
  EXPECT_NE(msg.find("more motion rows than the 1 frames declared"), std::string::npos) << msg;
}

TEST(BvhErrors, StructuralMistakes) {
  expect_error_at({}, 1);                           // empty
  expect_error_at({"HIERARCHY", "JOINT Hips"}, 2);  // no ROOT
  expect_error_at({"HIERARCHY", "ROOT", "{"}, 2);   // nameless root
  auto lines = base_lines();
  lines[3] = "";  // no OFFSET in Hips: reported at its '{'
  EXPECT_NE(expect_error_at(lines, 3).find("has no OFFSET"), std::string::npos);
  lines = base_lines();
  lines[15] = "MOTON";
  expect_error_at(lines, 16);
  lines = base_lines();
  lines[9] = "    End Sight";
  expect_error_at(lines, 10);
}

TEST(BvhRead, MissingFile) {
  try {
    performer::read_bvh("/nonexistent/dir/walk.bvh");
    FAIL() << "expected BvhError";
  } catch (const BvhError& e) {
    EXPECT_EQ(e.line(), 0);
    EXPECT_EQ(std::string(e.what()), "/nonexistent/dir/walk.bvh: cannot open file");
  }
}

}  // namespace
