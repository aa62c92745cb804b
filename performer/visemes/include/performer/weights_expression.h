// Expression overlay (thesis 3.4.4, equation 3.9): weights beta_j(t) for emotion DVs (smile,
// worry, ...) on top of the lip sync. The thesis sets them with sliders; here they come from
// keyframes, linearly interpolated, or a constant. At most two are kept per frame: the vertex
// shader has two expression DV streams (3.4.5).
//
// Keyframe file: one key per line, "time expression weight", seconds and a weight in [0, 1],
// separated by tabs or spaces; '#' comments; an expression's keys in time order. Before its first
// key and after its last an expression holds that key's weight (as animation curves do), so a
// single key is a constant. Two keys at the same time make a step.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace performer {

struct ExpressionKey {
  double time = 0.0;
  std::string expression;
  double weight = 0.0;
  int line = 0;
};

// Throws VisemeDataError ("FILE:LINE: problem") for a wrong field count, unreadable numbers, a
// weight outside [0, 1], or an expression's key earlier than its previous one.
std::vector<ExpressionKey> parse_expression_keys(std::string_view text, std::string_view file_name = "<expressions>");
std::vector<ExpressionKey> read_expression_keys(const std::filesystem::path& file);

// One key: the expression held at `weight` throughout. Throws std::invalid_argument for a weight
// outside [0, 1] or an empty name.
std::vector<ExpressionKey> constant_expression(std::string expression, double weight);

// Expression names in order of first appearance: the channel order.
std::vector<std::string> expression_names(std::span<const ExpressionKey> keys);

// beta for one expression at t (0 when it has no key). Keys of the expression must be in time
// order, as the parser guarantees.
double expression_weight(std::span<const ExpressionKey> keys, std::string_view expression, double t);

// One frame: out[j] = beta of names[j] at t, then all but the `max_expressions` strongest zeroed.
void expression_weights_at(std::span<const ExpressionKey> keys, std::span<const std::string> names, double t,
                           int max_expressions, std::span<float> out);

}  // namespace performer
