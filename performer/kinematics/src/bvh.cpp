// BVH reader: a parser over BvhLexer tokens, walking the joint nesting with an explicit stack.
//
//   file      := HIERARCHY root+ MOTION Frames: INT Frame Time: NUMBER row*
//   root      := ROOT name body          (name: the rest of the keyword's line)
//   body      := { (OFFSET x y z | CHANNELS n name*n | JOINT name body | End Site endbody)* }
//   endbody   := { OFFSET x y z }
//
// Channel values are numbered in the order CHANNELS lines appear, which is what every writer does
// (depth-first) and what motion rows follow.
#include "performer/bvh.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include "bvh_lexer.h"

namespace performer {

BvhError::BvhError(std::string file, int line, std::string problem)
    : std::runtime_error(line > 0 ? file + ":" + std::to_string(line) + ": " + problem : file + ": " + problem),
      file_(std::move(file)),
      line_(line),
      problem_(std::move(problem)) {}

namespace {

using detail::BvhLexer;
using detail::Token;

// BVH writers disagree on letter case ("End Site", "End site", "MOTION"), so keywords and channel
// names compare without it. Joint names keep theirs.
bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const auto lower = [](char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; };
    if (lower(a[i]) != lower(b[i])) return false;
  }
  return true;
}

std::optional<Channel> parse_channel(std::string_view text) {
  static constexpr std::array<Channel, 6> all{Channel::Xposition, Channel::Yposition, Channel::Zposition,
                                              Channel::Xrotation, Channel::Yrotation, Channel::Zrotation};
  for (Channel c : all)
    if (iequals(text, channel_name(c))) return c;
  return std::nullopt;
}

// from_chars rejects a leading '+', which some writers emit for positive values.
std::string_view without_plus(std::string_view text) {
  return (text.size() > 1 && text[0] == '+') ? text.substr(1) : text;
}

std::optional<double> parse_number(std::string_view text) {
  text = without_plus(text);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<long long> parse_integer(std::string_view text) {
  text = without_plus(text);
  long long value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

// Quotes a token for a message; the end of input has no text of its own.
// (Built by appending: GCC 12 warns falsely (-Wrestrict) on "'" + std::string(...).)
std::string quoted(const Token& t) {
  if (t.end()) return "end of file";
  std::string q;
  q.reserve(t.text.size() + 2);
  q.append(1, '\'').append(t.text).append(1, '\'');
  return q;
}

class Parser {
 public:
  Parser(std::string_view text, std::string_view file) : lex_(text), file_(file), text_size_(text.size()) {}

  Bvh parse() {
    expect_keyword("HIERARCHY", "at the start of the file");
    Token t = lex_.next();
    if (!iequals(t.text, "ROOT")) fail(t, "expected ROOT after HIERARCHY, found " + quoted(t));
    while (true) {
      parse_hierarchy(t);
      t = lex_.next();
      if (iequals(t.text, "ROOT")) continue;
      if (iequals(t.text, "MOTION")) break;
      fail(t, "expected ROOT or MOTION after the hierarchy, found " + quoted(t));
    }
    parse_motion();
    return std::move(out_);
  }

 private:
  // A joint whose '}' has not been seen yet.
  struct OpenJoint {
    int index;         // into out_.skeleton.joints
    int brace_line;    // line of its '{'
    std::string what;  // "joint Hips" / "End Site of Head", for messages
    bool has_offset = false;
    bool has_channels = false;
  };

  [[noreturn]] void fail(int line, std::string problem) const { throw BvhError(file_, line, std::move(problem)); }
  // At the end of input the token's own line is one past the content; report the last real line.
  [[noreturn]] void fail(const Token& t, std::string problem) const {
    fail(t.end() ? lex_.last_line() : t.line, std::move(problem));
  }

  void expect_keyword(std::string_view keyword, std::string_view where) {
    const Token t = lex_.next();
    if (!iequals(t.text, keyword))
      fail(t, "expected " + std::string(keyword) + " " + std::string(where) + ", found " + quoted(t));
  }

  Joint& joint_at(int index) { return out_.skeleton.joints[static_cast<std::size_t>(index)]; }

  // Appends a joint and opens its body, consuming its '{'.
  void open_joint(Joint joint, const std::string& what, std::string_view after) {
    const Token brace = lex_.next();
    if (brace.text != "{") fail(brace, "expected '{' after " + std::string(after) + ", found " + quoted(brace));
    // Overwritten by CHANNELS; a joint without it keeps where its values would have started.
    joint.channel_offset = channel_total_;
    open_.push_back(OpenJoint{static_cast<int>(out_.skeleton.joints.size()), brace.line, what});
    out_.skeleton.joints.push_back(std::move(joint));
  }

  // `keyword` is a ROOT or JOINT token; the name is what follows it on the same line, so names with
  // blanks survive.
  void open_named_joint(const Token& keyword, int parent) {
    std::string name;
    while (true) {
      const Token t = lex_.peek();
      if (t.end() || t.line != keyword.line || t.text == "{" || t.text == "}") break;
      if (!name.empty()) name += ' ';
      name += lex_.next().text;
    }
    if (name.empty()) fail(keyword, std::string(keyword.text) + " without a name");
    Joint joint;
    joint.name = name;
    joint.parent = parent;
    open_joint(std::move(joint), "joint " + name, std::string(keyword.text) + " " + name);
  }

  // One ROOT and everything below it. Iterative, with open_ as the stack of unclosed joints: the
  // nesting depth comes from the file, and a corrupt or hostile file must not overflow the call stack.
  void parse_hierarchy(const Token& root) {
    open_named_joint(root, -1);
    while (!open_.empty()) {
      const Token t = lex_.next();
      // By value: opening a child below grows open_.
      const int index = open_.back().index;
      const std::string what = open_.back().what;
      const bool end_site = joint_at(index).end_site;
      const std::string opened = " (opened on line " + std::to_string(open_.back().brace_line) + ")";
      if (t.end()) fail(t, "unexpected end of file: " + what + opened + " is missing its '}'");
      if (t.text == "}") {
        if (!open_.back().has_offset) fail(open_.back().brace_line, what + " has no OFFSET");
        open_.pop_back();
      } else if (iequals(t.text, "OFFSET")) {
        if (open_.back().has_offset) fail(t, "second OFFSET in " + what);
        open_.back().has_offset = true;
        glm::vec3 offset{0.0f};
        for (int axis = 0; axis < 3; ++axis) offset[axis] = read_float("OFFSET of " + what + " needs 3 numbers");
        joint_at(index).offset = offset;
      } else if (iequals(t.text, "CHANNELS")) {
        if (end_site) fail(t, "an End Site cannot have CHANNELS");
        if (open_.back().has_channels) fail(t, "second CHANNELS in " + what);
        open_.back().has_channels = true;
        parse_channels(index, t, what);
      } else if (iequals(t.text, "JOINT")) {
        if (end_site) fail(t, "an End Site cannot have child joints");
        open_named_joint(t, index);
      } else if (iequals(t.text, "End")) {
        if (end_site) fail(t, "an End Site cannot have child joints");
        const Token site = lex_.next();
        if (!iequals(site.text, "Site")) fail(site, "expected 'Site' after 'End', found " + quoted(site));
        Joint leaf;
        // End sites have no name in BVH; deriving one keeps names unique for find_joint.
        leaf.name = joint_at(index).name + "_end";
        leaf.parent = index;
        leaf.end_site = true;
        open_joint(std::move(leaf), "End Site of " + joint_at(index).name, "End Site");
      } else {
        // Covers a missing '}' as well: the next JOINT/MOTION/ROOT keyword lands here.
        fail(t, "expected OFFSET, CHANNELS, JOINT, End Site or '}' in " + what + opened + ", found " + quoted(t));
      }
    }
  }

  void parse_channels(int index, const Token& keyword, const std::string& what) {
    const Token count_token = lex_.next();
    const auto count = parse_integer(count_token.text);
    if (!count) fail(count_token, "expected a channel count after CHANNELS, found " + quoted(count_token));
    if (*count < 0 || *count > 6)
      fail(count_token, "CHANNELS count " + std::to_string(*count) + " in " + what + " (must be 0 to 6)");
    Joint& joint = joint_at(index);  // safe: nothing below adds joints
    joint.channel_offset = channel_total_;
    for (long long i = 0; i < *count; ++i) {
      const Token t = lex_.next();
      const auto channel = parse_channel(t.text);
      if (!channel) {
        // A structural word here means the list is shorter than announced, not a misspelt channel.
        const bool structural = t.end() || t.text == "{" || t.text == "}" || iequals(t.text, "JOINT") ||
                                iequals(t.text, "End") || iequals(t.text, "OFFSET") || iequals(t.text, "MOTION") ||
                                iequals(t.text, "CHANNELS") || iequals(t.text, "ROOT");
        if (structural)
          fail(keyword.line,
               "CHANNELS announces " + std::to_string(*count) + " channels but lists " + std::to_string(i));
        fail(t, "unknown channel " + quoted(t) +
                    " (expected Xposition, Yposition, Zposition, Xrotation, Yrotation or Zrotation)");
      }
      for (Channel seen : joint.channels)
        if (seen == *channel) fail(t, std::string(channel_name(*channel)) + " listed twice in " + what);
      joint.channels.push_back(*channel);
    }
    channel_total_ += static_cast<int>(*count);
  }

  float read_float(const std::string& need) {
    const Token t = lex_.next();
    const auto value = parse_number(t.text);
    if (!value) fail(t, need + ", found " + quoted(t));
    if (std::abs(*value) > std::numeric_limits<float>::max()) fail(t, quoted(t) + " is out of range");
    return static_cast<float>(*value);
  }

  // The value after "Frames:" or "Time:", which must be on the label's line (a missing number is
  // reported there, not on whatever line comes next). Labels are sometimes glued to their number
  // ("Frames:994").
  Token after_label(std::string_view label, std::string_view where, std::string_view value_name) {
    const Token t = lex_.next();
    if (t.text.size() > label.size() && iequals(t.text.substr(0, label.size()), label))
      return Token{t.text.substr(label.size()), t.line};
    if (!iequals(t.text, label))
      fail(t, "expected '" + std::string(label) + "' " + std::string(where) + ", found " + quoted(t));
    const Token value = lex_.peek();
    if (value.end() || value.line != t.line)
      fail(t.line, "missing " + std::string(value_name) + " after '" + std::string(label) + "'");
    return lex_.next();
  }

  void parse_motion() {
    const Token frames_token = after_label("Frames:", "after MOTION", "frame count");
    const auto frames = parse_integer(frames_token.text);
    if (!frames) fail(frames_token, "expected the frame count after 'Frames:', found " + quoted(frames_token));
    if (*frames < 0) fail(frames_token, "negative frame count " + std::to_string(*frames));
    if (*frames > std::numeric_limits<int>::max())
      fail(frames_token, "frame count " + std::to_string(*frames) + " too large");

    expect_keyword("Frame", "after the frame count ('Frame Time:')");
    const Token time_token = after_label("Time:", "after 'Frame'", "frame time");
    const auto frame_time = parse_number(time_token.text);
    if (!frame_time) fail(time_token, "expected the frame time after 'Frame Time:', found " + quoted(time_token));
    if (*frame_time <= 0.0) fail(time_token, "frame time must be positive, found " + quoted(time_token));

    Motion& motion = out_.motion;
    motion.frames = static_cast<int>(*frames);
    motion.frame_time = *frame_time;
    const auto channels = static_cast<std::size_t>(channel_total_);
    // Every value takes at least two characters ("0 "), which bounds what the text can hold: a
    // corrupt "Frames:" cannot make the reservation allocate wildly.
    motion.values.reserve(std::min(channels * static_cast<std::size_t>(*frames), text_size_ / 2 + 1));

    // A skeleton without channels has empty rows, i.e. nothing to read.
    if (channels > 0) {
      for (int row = 0; row < motion.frames; ++row) read_row(row, channels);
    }
    const Token extra = lex_.next();
    if (!extra.end())
      fail(extra, "more motion rows than the " + std::to_string(motion.frames) + " frames declared" +
                      (channels == 0 ? " (the skeleton has no channels)" : ""));
  }

  void read_row(int row, std::size_t channels) {
    const Token first = lex_.peek();
    if (first.end())
      fail(first, "unexpected end of file: " + std::to_string(row) + " motion rows of the " +
                      std::to_string(out_.motion.frames) + " declared");
    const int line = first.line;
    std::size_t count = 0;
    while (true) {
      const Token t = lex_.peek();
      if (t.end() || t.line != line) break;
      lex_.next();
      if (count < channels) {
        const auto value = parse_number(t.text);
        if (!value || std::abs(*value) > std::numeric_limits<float>::max())
          fail(t, "non-numeric value " + quoted(t) + " in motion row " + std::to_string(row + 1) + " (" +
                      describe_channel(count) + ")");
        out_.motion.values.push_back(static_cast<float>(*value));
      }
      ++count;
    }
    if (count != channels)
      fail(line, "motion row " + std::to_string(row + 1) + " has " + std::to_string(count) + " values, expected " +
                     std::to_string(channels));
  }

  // "Xrotation of LeftKnee" for the value at `index` within a row.
  std::string describe_channel(std::size_t index) const {
    for (const Joint& joint : out_.skeleton.joints) {
      const auto first = static_cast<std::size_t>(joint.channel_offset);
      if (index >= first && index < first + joint.channels.size())
        return std::string(channel_name(joint.channels[index - first])) + " of " + joint.name;
    }
    return "value " + std::to_string(index + 1);
  }

  BvhLexer lex_;
  std::string file_;
  Bvh out_;
  std::size_t text_size_;
  std::vector<OpenJoint> open_;
  int channel_total_ = 0;
};

}  // namespace

Bvh parse_bvh(std::string_view text, std::string_view file_name) { return Parser(text, file_name).parse(); }

Bvh read_bvh(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw BvhError(path.string(), 0, "cannot open file");
  std::ostringstream content;
  content << in.rdbuf();
  if (in.bad()) throw BvhError(path.string(), 0, "read error");
  return parse_bvh(content.view(), path.string());
}

}  // namespace performer
