#include "performer/weights_input.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "performer/viseme_error.h"

namespace performer {

namespace {

// Splits one CSV line into fields; a quoted field may hold commas and doubled quotes. Returns false
// for an unterminated quote.
bool split_csv(std::string_view line, std::vector<std::string>& fields) {
  fields.clear();
  std::string field;
  bool quoted = false, was_quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c != '"') {
        field += c;
      } else if (i + 1 < line.size() && line[i + 1] == '"') {
        field += '"';
        ++i;
      } else {
        quoted = false;
      }
    } else if (c == '"' && field.empty() && !was_quoted) {
      quoted = was_quoted = true;
    } else if (c == ',') {
      fields.push_back(std::move(field));
      field.clear();
      was_quoted = false;
    } else {
      field += c;
    }
  }
  fields.push_back(std::move(field));
  return !quoted;
}

bool parse_number(std::string_view s, double& value) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  if (s.empty()) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), value);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && std::isfinite(value);
}

}  // namespace

WeightTrack parse_weights_csv(std::string_view text, std::string_view file_name, const VisemeSet& set) {
  const std::string file(file_name);
  if (text.size() >= 3 && text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // UTF-8 BOM
  WeightTrack track;
  std::vector<std::string> fields;
  int line_number = 0;
  bool header = false;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    text.remove_prefix(end == std::string_view::npos ? text.size() : end + 1);
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.find_first_not_of(" \t") == std::string_view::npos) continue;
    if (!split_csv(line, fields)) throw VisemeDataError(file, line_number, "unterminated quote");
    if (!header) {
      if (fields.front() != "time")
        throw VisemeDataError(file, line_number,
                              "the header's first column must be \"time\", not \"" + fields.front() + "\"");
      if (fields.size() < 2) throw VisemeDataError(file, line_number, "the header names no weight channel");
      std::set<std::string> seen;
      for (std::size_t i = 1; i < fields.size(); ++i) {
        if (fields[i].empty())
          throw VisemeDataError(file, line_number, "channel " + std::to_string(i) + " has no name");
        if (!seen.insert(fields[i]).second)
          throw VisemeDataError(file, line_number, "channel \"" + fields[i] + "\" appears twice");
        track.channels.push_back(fields[i]);
      }
      while (track.viseme_channels < static_cast<int>(track.channels.size()) &&
             set.find(track.channels[static_cast<std::size_t>(track.viseme_channels)]) >= 0)
        ++track.viseme_channels;
      header = true;
      continue;
    }
    if (fields.size() != track.channels.size() + 1)
      throw VisemeDataError(
          file, line_number,
          "expected " + std::to_string(track.channels.size() + 1) + " fields, found " + std::to_string(fields.size()));
    double t = 0;
    if (!parse_number(fields[0], t))
      throw VisemeDataError(file, line_number, "time \"" + fields[0] + "\" is not a number");
    if (!track.times.empty() && t <= track.times.back())
      throw VisemeDataError(file, line_number, "time " + fields[0] + " does not come after the previous row's");
    track.times.push_back(t);
    for (std::size_t i = 1; i < fields.size(); ++i) {
      double w = 0;
      if (!parse_number(fields[i], w))
        throw VisemeDataError(
            file, line_number,
            "weight \"" + fields[i] + "\" of channel \"" + track.channels[i - 1] + "\" is not a number");
      if (w < 0 || w > 1)
        throw VisemeDataError(
            file, line_number,
            "weight " + fields[i] + " of channel \"" + track.channels[i - 1] + "\" is outside [0, 1]");
      track.values.push_back(static_cast<float>(w));
    }
  }
  if (!header) throw VisemeDataError(file, 0, "no header line (\"time,<channel>,...\")");
  if (track.times.empty()) throw VisemeDataError(file, 0, "no frames after the header");
  // Times are written to the microsecond, so the mean interval gives the rate to about 1e-5 over a
  // second of frames; rates are chosen in round numbers, so round to a thousandth of a frame.
  track.fps = track.times.size() > 1 ? std::round(1000.0 * static_cast<double>(track.times.size() - 1) /
                                                  (track.times.back() - track.times.front())) /
                                           1000.0
                                     : 30.0;
  return track;
}

WeightTrack read_weights_csv(const std::filesystem::path& file, const VisemeSet& set) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw VisemeDataError(file.string(), 0, "cannot open");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_weights_csv(ss.str(), file.string(), set);
}

}  // namespace performer
