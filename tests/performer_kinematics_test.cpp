// Tests for forward kinematics, sampling and two-bone IK (thesis 3.5.2-3.5.3). Expected values are
// computed here independently: rotation matrices written out element by element in double, composed
// by hand along the joint chain, never through the library's own FK.

#include <gtest/gtest.h>

#include "support/shared_assets.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "performer/bvh.h"
#include "performer/local_transforms.h"
#include "performer/pose.h"
#include "performer/sample.h"
#include "performer/skeleton.h"
#include "performer/two_bone_ik.h"
#include "performer/world_transforms.h"

namespace fs = std::filesystem;
using performer::Channel;
using performer::Joint;
using performer::Skeleton;

namespace {

constexpr double kPi = std::numbers::pi;
double rad(double degrees) { return degrees * kPi / 180.0; }

using test_support::bvh_asset;
#define REQUIRE_BVH_ASSET(path) REQUIRE_SHARED_FILE(path)

// Row-major 3x3 written the way textbooks print it, turned into glm's column-major storage.
glm::dmat3 rows(double a, double b, double c, double d, double e, double f, double g, double h, double i) {
  return glm::transpose(glm::dmat3(a, b, c, d, e, f, g, h, i));
}
glm::dmat3 Rx(double deg) {
  const double c = std::cos(rad(deg)), s = std::sin(rad(deg));
  return rows(1, 0, 0, 0, c, -s, 0, s, c);
}
glm::dmat3 Ry(double deg) {
  const double c = std::cos(rad(deg)), s = std::sin(rad(deg));
  return rows(c, 0, s, 0, 1, 0, -s, 0, c);
}
glm::dmat3 Rz(double deg) {
  const double c = std::cos(rad(deg)), s = std::sin(rad(deg));
  return rows(c, -s, 0, s, c, 0, 0, 0, 1);
}

glm::dmat4 rigid(const glm::dmat3& r, const glm::dvec3& t) {
  glm::dmat4 m(r);
  m[3] = glm::dvec4(t, 1.0);
  return m;
}

Joint make_joint(std::string name, int parent, glm::vec3 offset, std::vector<Channel> channels, int channel_offset,
                 bool end_site = false) {
  Joint j;
  j.name = std::move(name);
  j.parent = parent;
  j.offset = offset;
  j.channels = std::move(channels);
  j.channel_offset = channel_offset;
  j.end_site = end_site;
  return j;
}

std::vector<glm::mat4> fk(const Skeleton& sk, std::span<const float> row) {
  std::vector<glm::mat4> local(sk.joints.size()), world(sk.joints.size());
  performer::local_transforms(sk, row, local);
  performer::world_transforms(sk, local, world);
  return world;
}

// --- Forward kinematics -------------------------------------------------------------------------

// Equation 3.14: the planar two-link chain of figure 3.15 as a BVH skeleton rotating about Z.
TEST(ForwardKinematics, PlanarTwoBoneChainMatchesEquation314) {
  const float l1 = 3.0f, l2 = 2.0f;
  Skeleton sk;
  sk.joints.push_back(make_joint("shoulder", -1, {0, 0, 0}, {Channel::Zrotation}, 0));
  sk.joints.push_back(make_joint("elbow", 0, {l1, 0, 0}, {Channel::Zrotation}, 1));
  sk.joints.push_back(make_joint("hand", 1, {l2, 0, 0}, {}, 2, true));
  for (const auto& [t1, t2] : std::vector<std::pair<float, float>>{
           {0, 0}, {30, 45}, {90, -90}, {-60, 120}, {135, 170}, {200, -35}, {-179, 1}, {12.5f, 300}}) {
    const std::vector<float> row{t1, t2};
    const auto world = fk(sk, row);
    const double x = l1 * std::cos(rad(t1)) + l2 * std::cos(rad(t1 + t2));
    const double y = l1 * std::sin(rad(t1)) + l2 * std::sin(rad(t1 + t2));
    EXPECT_NEAR(world[2][3].x, x, 1e-5) << t1 << "," << t2;
    EXPECT_NEAR(world[2][3].y, y, 1e-5) << t1 << "," << t2;
    EXPECT_NEAR(world[2][3].z, 0.0, 1e-6);
    EXPECT_NEAR(world[1][3].x, l1 * std::cos(rad(t1)), 1e-5);
    EXPECT_NEAR(world[1][3].y, l1 * std::sin(rad(t1)), 1e-5);
    // The library's copy of 3.14 agrees too.
    const glm::dvec2 e = performer::planar_two_bone_fk(l1, l2, rad(t1), rad(t2));
    EXPECT_NEAR(e.x, x, 1e-12);
    EXPECT_NEAR(e.y, y, 1e-12);
  }
}

// Rotations multiply in listed order, and position channels add to the offset wherever they sit.
TEST(ForwardKinematics, ChannelOrderDefinesTheProduct) {
  Skeleton sk;
  sk.joints.push_back(make_joint("xyz", -1, {1, 2, 3},
                                 {Channel::Xrotation, Channel::Yposition, Channel::Yrotation, Channel::Zrotation}, 0));
  sk.joints.push_back(make_joint("zxy", 0, {0, 1, 0}, {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation}, 4));
  sk.joints.push_back(make_joint("yzx", 1, {0, 0, 2}, {Channel::Yrotation, Channel::Zrotation, Channel::Xrotation}, 7));
  const std::vector<float> row{10, 0.5f, 20, 30, 40, 50, 60, -70, 80, -90};
  std::vector<glm::mat4> local(3);
  performer::local_transforms(sk, row, local);
  const glm::dmat3 r0 = Rx(10) * Ry(20) * Rz(30);
  const glm::dmat3 r1 = Rz(40) * Rx(50) * Ry(60);
  const glm::dmat3 r2 = Ry(-70) * Rz(80) * Rx(-90);
  const glm::dmat4 expected_local[3] = {rigid(r0, {1, 2.5, 3}), rigid(r1, {0, 1, 0}), rigid(r2, {0, 0, 2})};
  for (int j = 0; j < 3; ++j)
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) EXPECT_NEAR(local[j][c][r], expected_local[j][c][r], 1e-6) << j << " " << c << r;

  std::vector<glm::mat4> world(3);
  performer::world_transforms(sk, local, world);
  const glm::dmat4 w2 = expected_local[0] * expected_local[1] * expected_local[2];
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(world[2][c][r], w2[c][r], 1e-5);
}

TEST(ForwardKinematics, RestPoseIsTheOffsets) {
  Skeleton sk;
  sk.joints.push_back(make_joint("a", -1, {1, 0, 0}, {Channel::Zrotation}, 0));
  sk.joints.push_back(make_joint("b", 0, {0, 2, 0}, {Channel::Xposition}, 1));
  std::vector<glm::mat4> rest(2), zero(2);
  performer::rest_local_transforms(sk, rest);
  const std::vector<float> zeros{0, 0};
  performer::local_transforms(sk, zeros, zero);
  EXPECT_EQ(rest, zero);
}

TEST(ForwardKinematics, RejectsMismatchedSpans) {
  Skeleton sk;
  sk.joints.push_back(make_joint("a", -1, {0, 0, 0}, {Channel::Zrotation}, 0));
  std::vector<glm::mat4> out(1), two(2);
  const std::vector<float> row{1, 2};
  EXPECT_THROW(performer::local_transforms(sk, row, out), std::invalid_argument);
  EXPECT_THROW(performer::world_transforms(sk, out, two), std::invalid_argument);
  Skeleton backwards;
  backwards.joints.push_back(make_joint("child", 1, {0, 0, 0}, {}, 0));
  backwards.joints.push_back(make_joint("root", -1, {0, 0, 0}, {}, 0));
  std::vector<glm::mat4> l2(2, glm::mat4(1.0f));
  EXPECT_THROW(performer::world_transforms(backwards, l2, two), std::invalid_argument);
}

// One CMU frame, checked joint by joint against matrices composed by hand from the raw channel
// values: root T(position) * Rz * Ry * Rx, legs/spine T(offset) * Rz * Ry * Rx, arms (written
// "Zrotation Xrotation Yrotation" in these files) T(offset) * Rz * Rx * Ry.
TEST(ForwardKinematics, CmuFrameAgainstHandComposedMatrices) {
  const fs::path path = bvh_asset("cmu_131_01.bvh");
  REQUIRE_BVH_ASSET(path);
  const performer::Bvh bvh = performer::read_bvh(path);
  const Skeleton& sk = bvh.skeleton;
  const std::vector<std::string> arm{"LeftShoulder",  "LeftElbow",  "LeftWrist",  "lhand", "LFingers", "LThumb",
                                     "RightShoulder", "RightElbow", "RightWrist", "rhand", "RFingers", "RThumb"};

  for (const int frame : {0, 377, bvh.motion.frames - 1}) {
    const std::span<const float> row = performer::frame_values(sk, bvh.motion, frame);
    const auto world = fk(sk, row);
    for (const char* target : {"LeftWrist", "RThumb_end", "Head_end", "LeftToe_end", "RightKnee"}) {
      const int index = performer::find_joint(sk, target);
      ASSERT_GE(index, 0) << target;
      // Walk up to the root, then compose downwards.
      std::vector<int> chain;
      for (int j = index; j >= 0; j = sk.joints[static_cast<std::size_t>(j)].parent) chain.insert(chain.begin(), j);
      glm::dmat4 m(1.0);
      for (const int j : chain) {
        const Joint& joint = sk.joints[static_cast<std::size_t>(j)];
        // This joint's raw values, in file order.
        std::vector<double> raw;
        for (std::size_t c = 0; c < joint.channels.size(); ++c)
          raw.push_back(row[static_cast<std::size_t>(joint.channel_offset) + c]);
        const double* v = raw.data();
        const glm::dvec3 offset(joint.offset);
        if (j == 0) {
          m = m * rigid(Rz(v[3]) * Ry(v[4]) * Rx(v[5]), offset + glm::dvec3(v[0], v[1], v[2]));
        } else if (joint.end_site) {
          m = m * rigid(glm::dmat3(1.0), offset);
        } else if (std::find(arm.begin(), arm.end(), joint.name) != arm.end()) {
          m = m * rigid(Rz(v[0]) * Rx(v[1]) * Ry(v[2]), offset);
        } else {
          m = m * rigid(Rz(v[0]) * Ry(v[1]) * Rx(v[2]), offset);
        }
      }
      const glm::mat4& got = world[static_cast<std::size_t>(index)];
      for (int r = 0; r < 3; ++r) EXPECT_NEAR(got[3][r], m[3][r], 1e-3) << target << " frame " << frame;
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) EXPECT_NEAR(got[c][r], m[c][r], 1e-5) << target << " frame " << frame;
    }
  }
}

// --- Poses and sampling -------------------------------------------------------------------------

glm::dquat qaxis(int axis, double deg) {
  glm::dvec3 a(0.0);
  a[axis] = 1.0;
  return glm::angleAxis(rad(deg), a);
}

TEST(Pose, QuaternionsMatchTheMatrices) {
  Skeleton sk;
  sk.joints.push_back(make_joint("root", -1, {0, 0, 0},
                                 {Channel::Xposition, Channel::Yposition, Channel::Zposition, Channel::Zrotation,
                                  Channel::Yrotation, Channel::Xrotation},
                                 0));
  sk.joints.push_back(make_joint("zxy", 0, {0, 1, 0}, {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation}, 6));
  const std::vector<float> row{1, 2, 3, 100, -40, 75, 33, -120, 250};
  std::vector<performer::JointPose> poses(2);
  performer::decode_pose(sk, row, poses);
  const glm::dquat q0 = qaxis(2, 100) * qaxis(1, -40) * qaxis(0, 75);
  const glm::dquat q1 = qaxis(2, 33) * qaxis(0, -120) * qaxis(1, 250);
  EXPECT_NEAR(std::abs(glm::dot(glm::dquat(poses[0].rotation), q0)), 1.0, 1e-6);
  EXPECT_NEAR(std::abs(glm::dot(glm::dquat(poses[1].rotation), q1)), 1.0, 1e-6);
  EXPECT_EQ(poses[0].translation, glm::vec3(1, 2, 3));
  std::vector<glm::mat4> from_poses(2), direct(2);
  performer::poses_to_local(poses, from_poses);
  performer::local_transforms(sk, row, direct);
  for (int j = 0; j < 2; ++j)
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) EXPECT_NEAR(from_poses[j][c][r], direct[j][c][r], 1e-6);
}

// Two root-only frames a near-half-turn apart about Z, plus a third for clamping.
struct TinyClip {
  Skeleton sk;
  performer::Motion motion;
  TinyClip() {
    sk.joints.push_back(make_joint("root", -1, {0.5f, 0, 0},
                                   {Channel::Xposition, Channel::Yposition, Channel::Zposition, Channel::Zrotation,
                                    Channel::Yrotation, Channel::Xrotation},
                                   0));
    sk.joints.push_back(make_joint("tip", 0, {1, 0, 0}, {}, 6, true));
    motion.frames = 3;
    motion.frame_time = 0.1;
    motion.values = {0, 0, 0,  170,  10, 0,   //
                     2, 4, -6, -170, 30, 20,  //
                     8, 8, 8,  0,    0,  90};
  }
};

TEST(Sample, AtFrameTimesReturnsTheFrameExactly) {
  TinyClip clip;
  std::vector<performer::JointPose> got(2), want(2);
  for (int f = 0; f < clip.motion.frames; ++f) {
    performer::sample(clip.sk, clip.motion, f * clip.motion.frame_time, got);
    performer::decode_pose(clip.sk, performer::frame_values(clip.sk, clip.motion, f), want);
    for (int j = 0; j < 2; ++j) {
      EXPECT_EQ(got[j].translation, want[j].translation) << f;
      EXPECT_EQ(got[j].rotation, want[j].rotation) << f;
    }
  }
}

TEST(Sample, MidwayIsLerpAndShortestSlerp) {
  TinyClip clip;
  std::vector<performer::JointPose> a(2), b(2), mid(2);
  performer::decode_pose(clip.sk, performer::frame_values(clip.sk, clip.motion, 0), a);
  performer::decode_pose(clip.sk, performer::frame_values(clip.sk, clip.motion, 1), b);
  for (const double t : {0.5, 0.25, 0.9}) {
    performer::sample(clip.sk, clip.motion, t * 0.1, mid);
    EXPECT_NEAR(glm::distance(mid[0].translation, glm::mix(a[0].translation, b[0].translation, float(t))), 0.0f, 1e-6f);
    // Reference slerp, in double, from the hand-built quaternions (glm::slerp takes the short arc).
    const glm::dquat qa = qaxis(2, 170) * qaxis(1, 10) * qaxis(0, 0);
    const glm::dquat qb = qaxis(2, -170) * qaxis(1, 30) * qaxis(0, 20);
    const glm::dquat q = glm::slerp(qa, qb, t);
    EXPECT_NEAR(std::abs(glm::dot(glm::dquat(mid[0].rotation), q)), 1.0, 1e-6) << t;
  }
  // Z went 170 -> -170: the short way passes 180, so the root's x axis points along -x midway.
  performer::sample(clip.sk, clip.motion, 0.05, mid);
  const glm::vec3 x_axis = mid[0].rotation * glm::vec3(1, 0, 0);
  EXPECT_LT(x_axis.x, -0.9f);
}

TEST(Sample, ClampsOutsideTheClip) {
  TinyClip clip;
  std::vector<performer::JointPose> got(2), first(2), last(2);
  performer::decode_pose(clip.sk, performer::frame_values(clip.sk, clip.motion, 0), first);
  performer::decode_pose(clip.sk, performer::frame_values(clip.sk, clip.motion, 2), last);
  for (const double t : {-1.0, -1e-9, std::nan("")}) {
    performer::sample(clip.sk, clip.motion, t, got);
    EXPECT_EQ(got[0].rotation, first[0].rotation) << t;
    EXPECT_EQ(got[0].translation, first[0].translation) << t;
  }
  for (const double t : {0.2, 0.2000001, 5.0, 1e30}) {
    performer::sample(clip.sk, clip.motion, t, got);
    EXPECT_EQ(got[0].rotation, last[0].rotation) << t;
    EXPECT_EQ(got[0].translation, last[0].translation) << t;
  }
  performer::Motion empty;
  empty.frame_time = 0.1;
  performer::sample(clip.sk, empty, 1.0, got);
  EXPECT_EQ(got[0].translation, glm::vec3(0.5f, 0, 0)) << "no frames: rest pose";
  EXPECT_EQ(got[0].rotation, glm::quat(1, 0, 0, 0));
}

TEST(Sample, CmuFramesExactAndMidwaySlerp) {
  const fs::path path = bvh_asset("cmu_131_03.bvh");
  REQUIRE_BVH_ASSET(path);
  const performer::Bvh bvh = performer::read_bvh(path);
  const Skeleton& sk = bvh.skeleton;
  const std::size_t n = sk.joints.size();
  std::vector<performer::JointPose> got(n), a(n), b(n);
  for (int f = 0; f < bvh.motion.frames; ++f) {
    performer::decode_pose(sk, performer::frame_values(sk, bvh.motion, f), a);
    performer::sample(sk, bvh.motion, f * bvh.motion.frame_time, got);
    for (std::size_t j = 0; j < n; ++j) {
      ASSERT_EQ(got[j].rotation, a[j].rotation) << "frame " << f << " joint " << sk.joints[j].name;
      ASSERT_EQ(got[j].translation, a[j].translation) << "frame " << f;
    }
    if (f + 1 == bvh.motion.frames || f % 7 != 0) continue;
    performer::decode_pose(sk, performer::frame_values(sk, bvh.motion, f + 1), b);
    performer::sample(sk, bvh.motion, (f + 0.5) * bvh.motion.frame_time, got);
    for (std::size_t j = 0; j < n; ++j) {
      EXPECT_NEAR(glm::distance(got[j].translation, 0.5f * (a[j].translation + b[j].translation)), 0.0f, 1e-4f);
      const glm::dquat ref = glm::slerp(glm::dquat(a[j].rotation), glm::dquat(b[j].rotation), 0.5);
      EXPECT_NEAR(std::abs(glm::dot(glm::dquat(got[j].rotation), ref)), 1.0, 1e-6) << f << " " << sk.joints[j].name;
    }
  }
}

// --- Two-bone IK --------------------------------------------------------------------------------

TEST(TwoBoneIk, PlanarReachableTargetsRoundTrip) {
  std::mt19937 rng(131);
  std::uniform_real_distribution<double> length(0.2, 3.0), unit(0.0, 1.0), angle(-kPi, kPi);
  for (int i = 0; i < 2000; ++i) {
    const double l1 = length(rng), l2 = length(rng);
    const double lo = std::abs(l1 - l2), hi = l1 + l2;
    const double d = lo + (hi - lo) * unit(rng);
    const double phi = angle(rng);
    const glm::dvec2 target(d * std::cos(phi), d * std::sin(phi));
    for (const bool bend : {true, false}) {
      const auto s = performer::solve_planar_two_bone(l1, l2, target, bend);
      EXPECT_TRUE(s.reachable);
      const glm::dvec2 e = performer::planar_two_bone_fk(l1, l2, s.theta1, s.theta2);
      ASSERT_LT(glm::distance(e, target), 1e-6)
          << "l1=" << l1 << " l2=" << l2 << " target=" << target.x << "," << target.y;
      if (std::abs(s.theta2) > 1e-9) {
        EXPECT_EQ(s.theta2 > 0.0, bend);
      }
    }
  }
  // The extremes are reachable too.
  EXPECT_TRUE(performer::solve_planar_two_bone(2, 1, {3, 0}).reachable);
  EXPECT_TRUE(performer::solve_planar_two_bone(2, 1, {0, 1}).reachable);
}

TEST(TwoBoneIk, PlanarUnreachableTargetsReportedWithClosestReach) {
  struct Case {
    double l1, l2;
    glm::dvec2 target;
    double reach;  // distance of the closest reachable point along the target direction
  };
  for (const Case& c : {Case{2, 1, {3, 4}, 3.0},                                      // beyond l1 + l2
                        Case{2, 1, {-10, 0.5}, 3.0}, Case{2, 0.5, {0.3, -0.4}, 1.5},  // inside |l1 - l2|
                        Case{0.5, 2, {0.0, 0.2}, 1.5}}) {                             // inside, second bone longer
    const auto s = performer::solve_planar_two_bone(c.l1, c.l2, c.target);
    EXPECT_FALSE(s.reachable);
    const glm::dvec2 e = performer::planar_two_bone_fk(c.l1, c.l2, s.theta1, s.theta2);
    EXPECT_NEAR(glm::distance(e, glm::normalize(c.target) * c.reach), 0.0, 1e-9);
  }
  EXPECT_THROW(performer::solve_planar_two_bone(0, 1, {1, 0}), std::invalid_argument);
}

glm::dvec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<double> g;
  return glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
}

// The 3-D solver's output fed back through forward kinematics: the chain as world rotations of two
// joints and fixed bone offsets in their local frames, rotated by the solution, composed again.
TEST(TwoBoneIk, SpatialSolutionThroughForwardKinematics) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> length(0.3, 2.5), unit(0.0, 1.0), coord(-5.0, 5.0), angle(-kPi, kPi);
  for (int i = 0; i < 2000; ++i) {
    const double l1 = length(rng), l2 = length(rng);
    const glm::dvec3 root(coord(rng), coord(rng), coord(rng));
    // Bones along local +y, joints in arbitrary orientations: the rig's rest state.
    const glm::dquat r_root = glm::angleAxis(angle(rng), random_unit(rng));
    const glm::dquat r_mid = glm::angleAxis(angle(rng), random_unit(rng));
    const glm::dvec3 bone1(0, l1, 0), bone2(0, l2, 0);
    const performer::TwoBoneChain chain{root, root + r_root * bone1, root + r_root * bone1 + r_mid * bone2};

    const double lo = std::abs(l1 - l2), hi = l1 + l2;
    const double d = lo + (hi - lo) * (0.001 + 0.998 * unit(rng));
    const glm::dvec3 target = root + d * random_unit(rng);
    const glm::dvec3 pole = root + glm::dvec3(coord(rng), coord(rng), coord(rng));
    const performer::TwoBoneIkResult r = performer::solve_two_bone_ik(chain, target, pole);
    EXPECT_TRUE(r.reachable);

    // FK of the solved rotations.
    const glm::dquat w_root = r.root_rotation * r_root;
    const glm::dquat w_mid = r.mid_rotation * r.root_rotation * r_mid;
    const glm::dvec3 mid = root + w_root * bone1;
    const glm::dvec3 end = mid + w_mid * bone2;
    ASSERT_LT(glm::distance(end, target), 1e-6) << "case " << i;
    EXPECT_LT(glm::distance(mid, r.mid), 1e-9);
    EXPECT_LT(glm::distance(r.end, target), 1e-6);
    // The knee bends toward the pole: the mid joint is on the pole's side of the root-target line.
    const glm::dvec3 axis = glm::normalize(target - root);
    const glm::dvec3 pole_side = (pole - root) - glm::dot(pole - root, axis) * axis;
    const glm::dvec3 mid_side = (mid - root) - glm::dot(mid - root, axis) * axis;
    if (glm::length(pole_side) > 1e-6 && glm::length(mid_side) > 1e-6) {
      EXPECT_GT(glm::dot(pole_side, mid_side), 0.0);
    }
  }
}

TEST(TwoBoneIk, SpatialUnreachableReportsAndReachesClosest) {
  const performer::TwoBoneChain chain{{0, 0, 0}, {0, 2, 0}, {1, 2, 0}};  // l1 = 2, l2 = 1
  const glm::dvec3 pole(0, 0, 5);
  const auto far = performer::solve_two_bone_ik(chain, {10, 0, 0}, pole);
  EXPECT_FALSE(far.reachable);
  EXPECT_NEAR(glm::distance(far.end, glm::dvec3(3, 0, 0)), 0.0, 1e-9);
  const auto near = performer::solve_two_bone_ik(chain, {0.2, 0.1, 0}, pole);
  EXPECT_FALSE(near.reachable);
  EXPECT_NEAR(glm::length(near.end), 1.0, 1e-9) << "folded: end at |l1 - l2| from the root";
  const performer::TwoBoneChain broken{{0, 0, 0}, {0, 0, 0}, {1, 0, 0}};
  EXPECT_THROW(performer::solve_two_bone_ik(broken, {1, 0, 0}, pole), std::invalid_argument);
}

}  // namespace
