#include "head_poses.h"

#include <numbers>
#include <span>
#include <utility>

namespace performer::detail {

namespace {

constexpr float deg(float d) { return d * std::numbers::pi_v<float> / 180.0f; }

struct NamedPose {
  std::string_view name;
  FacePose pose;
};

// Mouth shapes follow the thesis' descriptions (Figure 3.5 and the notes in visemes.tsv): how far
// the jaw drops, whether the lips round, spread or press, and what the tongue and teeth do, kept
// moderate because speech blends neighbouring visemes (3.4.3) rather than hitting each extreme.
constexpr NamedPose kThesisVisemes[] = {
    {"closed", {}},  // the neutral face: DV zero (equation 3.5)
    {"IY",
     {.jaw_open = deg(3), .lip_spread = 0.8f, .upper_lip_raise = 0.2f, .lower_lip_drop = 0.2f, .corner_up = 0.15f}},
    {"EH", {.jaw_open = deg(8), .lip_spread = 0.5f, .upper_lip_raise = 0.25f, .lower_lip_drop = 0.3f}},
    {"AA", {.jaw_open = deg(11), .lip_round = 0.1f, .upper_lip_raise = 0.4f, .lower_lip_drop = 0.3f}},
    {"O", {.jaw_open = deg(9), .lip_round = 0.8f, .lip_protrude = 0.5f}},
    {"UH", {.jaw_open = deg(4), .lip_round = 1.0f, .lip_protrude = 1.0f}},
    {"Y", {.jaw_open = deg(2), .lip_spread = 0.6f, .upper_lip_raise = 0.1f, .lower_lip_drop = 0.1f}},
    // Tongue tip up at the teeth ridge: a little tongue shows in the opening.
    {"L", {.jaw_open = deg(7), .upper_lip_raise = 0.25f, .lower_lip_drop = 0.1f, .tongue_out = 0.25f}},
    {"M", {.lip_press = 1.0f}},
    {"N", {.jaw_open = deg(4), .upper_lip_raise = 0.15f, .lower_lip_drop = 0.1f, .tongue_out = 0.1f}},
    {"NG", {.jaw_open = deg(7), .lip_spread = 0.2f, .upper_lip_raise = 0.15f, .lower_lip_drop = 0.2f}},
    // Lower lip up and back against the upper teeth, the upper lip lifted off them.
    {"F", {.jaw_open = deg(2), .lower_lip_tuck = 1.0f, .upper_lip_raise = 0.5f}},
    {"TH", {.jaw_open = deg(5), .upper_lip_raise = 0.3f, .lower_lip_drop = 0.3f, .tongue_out = 1.0f}},
    {"S", {.jaw_open = deg(1.5f), .lip_spread = 0.7f, .upper_lip_raise = 0.35f, .lower_lip_drop = 0.35f}},
    {"SH",
     {.jaw_open = deg(3), .lip_round = 0.5f, .lip_protrude = 0.9f, .upper_lip_raise = 0.45f, .lower_lip_drop = 0.45f}},
    {"K", {.jaw_open = deg(8), .lip_spread = 0.15f, .upper_lip_raise = 0.2f, .lower_lip_drop = 0.2f}},
};

// For a viseme set with other names: the Oculus viseme it maps to picks the closest thesis shape.
constexpr std::pair<std::string_view, std::string_view> kOculusToThesis[] = {
    {"sil", "closed"}, {"PP", "M"}, {"FF", "F"},  {"TH", "TH"}, {"DD", "L"},  {"kk", "K"}, {"CH", "SH"},
    {"SS", "S"},       {"nn", "N"}, {"aa", "AA"}, {"E", "EH"},  {"ih", "IY"}, {"oh", "O"}, {"ou", "UH"},
};
// RR has no thesis viseme: a slightly rounded, half-open mouth.
constexpr FacePose kOculusRR = {.jaw_open = deg(5), .lip_round = 0.5f, .lip_protrude = 0.4f};

// Thesis Figure 3.11's expressions and the eye-action channel.
constexpr NamedPose kExpressions[] = {
    {"smile",
     {.jaw_open = deg(1.5f),
      .lip_spread = 0.35f,
      .upper_lip_raise = 0.15f,
      .corner_up = 1.0f,
      .cheek_raise = 1.0f,
      .lower_lid_up = 0.35f}},
    {"worry", {.lip_press = 0.2f, .corner_up = -0.35f, .brow_inner_up = 1.0f, .lid_close = 0.1f}},
    {"surprise",
     {.jaw_open = deg(10), .lip_round = 0.2f, .brow_inner_up = 0.8f, .brow_outer_up = 1.0f, .lid_close = -0.35f}},
    {"anger", {.lip_press = 0.6f, .corner_up = -0.25f, .brow_down = 1.0f, .lid_close = 0.25f, .lower_lid_up = 0.35f}},
    {"blink", {.lid_close = 1.0f}},
};

std::optional<FacePose> find(std::span<const NamedPose> table, std::string_view name) {
  for (const NamedPose& p : table)
    if (p.name == name) return p.pose;
  return std::nullopt;
}

}  // namespace

std::optional<FacePose> viseme_pose(std::string_view name, std::string_view oculus) {
  if (auto pose = find(kThesisVisemes, name)) return pose;
  if (oculus == "RR") return kOculusRR;
  for (const auto& [o, thesis] : kOculusToThesis)
    if (o == oculus) return find(kThesisVisemes, thesis);
  return std::nullopt;
}

std::optional<FacePose> expression_pose(std::string_view name) { return find(kExpressions, name); }

}  // namespace performer::detail
