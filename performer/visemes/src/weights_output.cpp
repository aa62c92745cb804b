#include "performer/weights_output.h"

#include <charconv>
#include <cstdio>
#include <string>
#include <string_view>

#include "base/json_string.h"

namespace performer {

namespace {

// Six decimals (microseconds; weights far below what a frame buffer shows), trailing zeros dropped.
std::string number(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 6);
  std::string s(buf, r.ptr);
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

// CSV fields are quoted only when they need it (RFC 4180).
std::string csv_field(std::string_view s) {
  if (s.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(s);
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

using base::json_string;

}  // namespace

void write_weights_csv(std::ostream& out, const WeightTrack& track) {
  out << "time";
  for (const std::string& c : track.channels) out << ',' << csv_field(c);
  out << '\n';
  for (std::size_t f = 0; f < track.frame_count(); ++f) {
    out << number(track.times[f]);
    for (float w : track.frame(f)) out << ',' << number(w);
    out << '\n';
  }
}

void write_weights_json(std::ostream& out, const WeightTrack& track) {
  out << "{\n  \"fps\": " << number(track.fps) << ",\n  \"channels\": [";
  for (std::size_t c = 0; c < track.channel_count(); ++c) out << (c ? ", " : "") << json_string(track.channels[c]);
  out << "],\n  \"time\": [";
  for (std::size_t f = 0; f < track.frame_count(); ++f) out << (f ? ", " : "") << number(track.times[f]);
  out << "],\n  \"weights\": {";
  for (std::size_t c = 0; c < track.channel_count(); ++c) {
    out << (c ? ",\n" : "\n") << "    " << json_string(track.channels[c]) << ": [";
    for (std::size_t f = 0; f < track.frame_count(); ++f)
      out << (f ? ", " : "") << number(track.values[f * track.channel_count() + c]);
    out << ']';
  }
  out << "\n  }\n}\n";
}

}  // namespace performer
