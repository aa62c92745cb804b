#include "performer/weights_expression.h"

#include <algorithm>
#include <stdexcept>

#include "performer/viseme_error.h"
#include "performer/weights_visemes.h"
#include "performer/detail/viseme_text.h"

namespace performer {

std::vector<ExpressionKey> parse_expression_keys(std::string_view text, std::string_view file_name) {
  const std::string file(file_name);
  std::vector<ExpressionKey> keys;
  for (const detail::TextLine& line : detail::content_lines(text)) {
    const auto fields = detail::split_fields(line.text);
    if (fields.size() != 3)
      throw VisemeDataError(file, line.number,
                            "expected 3 fields (time expression weight), found " + std::to_string(fields.size()));
    const auto time = detail::parse_number(fields[0]);
    if (!time) throw VisemeDataError(file, line.number, "time '" + std::string(fields[0]) + "' is not a number");
    const auto weight = detail::parse_number(fields[2]);
    if (!weight) throw VisemeDataError(file, line.number, "weight '" + std::string(fields[2]) + "' is not a number");
    if (*weight < 0.0 || *weight > 1.0) throw VisemeDataError(file, line.number, "weight outside [0, 1]");
    // Interpolation walks an expression's keys in file order; out-of-order keys would be silently
    // misread, so they are refused here.
    for (auto it = keys.rbegin(); it != keys.rend(); ++it)
      if (it->expression == fields[1]) {
        if (*time < it->time)
          throw VisemeDataError(
              file, line.number,
              "key for '" + it->expression + "' earlier than its key on line " + std::to_string(it->line));
        break;
      }
    keys.push_back({*time, std::string(fields[1]), *weight, line.number});
  }
  return keys;
}

std::vector<ExpressionKey> read_expression_keys(const std::filesystem::path& file) {
  return parse_expression_keys(detail::read_text_file(file), file.string());
}

std::vector<ExpressionKey> constant_expression(std::string expression, double weight) {
  if (expression.empty()) throw std::invalid_argument("constant_expression: empty name");
  if (!(weight >= 0.0 && weight <= 1.0)) throw std::invalid_argument("constant_expression: weight outside [0, 1]");
  return {ExpressionKey{0.0, std::move(expression), weight, 0}};
}

std::vector<std::string> expression_names(std::span<const ExpressionKey> keys) {
  std::vector<std::string> names;
  for (const ExpressionKey& k : keys)
    if (std::find(names.begin(), names.end(), k.expression) == names.end()) names.push_back(k.expression);
  return names;
}

double expression_weight(std::span<const ExpressionKey> keys, std::string_view expression, double t) {
  const ExpressionKey* before = nullptr;  // last key at or before t
  const ExpressionKey* after = nullptr;   // first key after t
  for (const ExpressionKey& k : keys) {
    if (k.expression != expression) continue;
    if (k.time <= t)
      before = &k;
    else if (!after)
      after = &k;
  }
  if (!before) return after ? after->weight : 0.0;
  if (!after) return before->weight;
  const double f = (t - before->time) / (after->time - before->time);
  return before->weight + (after->weight - before->weight) * f;
}

void expression_weights_at(std::span<const ExpressionKey> keys, std::span<const std::string> names, double t,
                           int max_expressions, std::span<float> out) {
  if (out.size() != names.size()) throw std::invalid_argument("expression_weights_at: one output per name");
  for (std::size_t j = 0; j < names.size(); ++j)
    out[j] = static_cast<float>(std::clamp(expression_weight(keys, names[j], t), 0.0, 1.0));
  keep_strongest(out, max_expressions);
}

}  // namespace performer
