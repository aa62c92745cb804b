// Rhubarb's JSON output: {"metadata": {...}, "mouthCues": [{"start": s, "end": e, "value": "A"}, ...]}.
// Only mouthCues is read; other members (metadata, anything a later Rhubarb adds) are skipped.
#include <optional>

#include "performer/viseme_error.h"
#include "performer/viseme_rhubarb.h"
#include "viseme_json.h"

namespace performer {

namespace {

MouthCue read_cue(detail::JsonCursor& json, double previous_start) {
  json.peek();
  const int line = json.line();  // errors about the cue as a whole point at its opening brace
  json.expect('{', "a cue object {\"start\", \"end\", \"value\"}");
  std::optional<double> start, end;
  std::optional<std::string> value;
  if (!json.consume('}')) {
    do {
      const std::string key = json.read_string();
      json.expect(':', "':'");
      if (key == "start")
        start = json.read_number();
      else if (key == "end")
        end = json.read_number();
      else if (key == "value")
        value = json.read_string();
      else
        json.skip_value();
    } while (json.consume(','));
    json.expect('}', "',' or '}'");
  }
  const auto fail = [&](const std::string& problem) { throw VisemeDataError(json.file_name(), line, problem); };
  if (!start || !end || !value) fail("cue needs \"start\", \"end\" and \"value\"");
  if (!is_rhubarb_shape(*value)) fail("'" + *value + "' is not a Rhubarb shape (A-H, X)");
  if (*end < *start) fail("cue ends before it starts");
  if (*start < previous_start) fail("cue starts before the previous one");
  return {*start, *end, *value, line};
}

}  // namespace

std::vector<MouthCue> parse_rhubarb_json(std::string_view text, std::string_view file_name) {
  detail::JsonCursor json(text, std::string(file_name));
  std::vector<MouthCue> cues;
  bool found = false;
  json.expect('{', "'{' (a Rhubarb JSON object)");
  if (!json.consume('}')) {
    do {
      const std::string key = json.read_string();
      json.expect(':', "':'");
      if (key != "mouthCues") {
        json.skip_value();
        continue;
      }
      if (found) json.fail("\"mouthCues\" given twice");
      found = true;
      json.expect('[', "'[' (the mouthCues array)");
      if (json.consume(']')) continue;
      do cues.push_back(read_cue(json, cues.empty() ? -1e300 : cues.back().start));
      while (json.consume(','));
      json.expect(']', "',' or ']'");
    } while (json.consume(','));
    json.expect('}', "',' or '}'");
  }
  json.expect_end();
  if (!found) throw VisemeDataError(std::string(file_name), 0, "no \"mouthCues\" array");
  return cues;
}

}  // namespace performer
