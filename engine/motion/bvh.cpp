// BVH import and export.
//
// Conventions (the Biovision format as Blender, MotionBuilder and the CMU conversions use it):
// - A joint's local transform is translate(OFFSET) · R, with R the product of its rotation channels in the
//   order they are listed (CHANNELS 3 Zrotation Xrotation Yrotation means R = Rz · Rx · Ry), in degrees.
// - The root's position channels are added to its OFFSET; we fold both into Pose::root_position and give
//   the skeleton's root a zero offset.
// - Position channels on a non-root joint cannot be represented by a Pose (one translation, at the root).
//   If their values are constant over the clip they are folded into the joint's offset: values equal to
//   the OFFSET restate it (MotionBuilder-style exports), other values are added to it. If they change over
//   the clip (a stretching bone) the file is rejected.
// Numbers are parsed with std::from_chars, so the process locale (a comma decimal separator) never matters.
// Lengths, once scaled to metres, must lie within kMaxLength and the frame time within [kMinFrameTime,
// kMaxFrameTime]: larger numbers are finite in the file's doubles but not in our floats (an OFFSET of 1e39
// read as infinity), and no capture is kilometres across or filmed at a megahertz.
#include "engine/motion/bvh.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <glm/gtc/quaternion.hpp>
#include <string_view>
#include <system_error>
#include <unordered_set>

#include "engine/motion/pose.h"
#include "engine/util/error.h"
#include "engine/util/files.h"

namespace prep {
namespace {

constexpr double kMaxLength = 1e6;  // metres
constexpr double kMinFrameTime = 1e-5, kMaxFrameTime = 1e4;  // seconds

enum class Channel { Xpos, Ypos, Zpos, Xrot, Yrot, Zrot };

bool is_position(Channel c) { return c == Channel::Xpos || c == Channel::Ypos || c == Channel::Zpos; }
int axis_of(Channel c) {
  switch (c) {
    case Channel::Xpos: case Channel::Xrot: return 0;
    case Channel::Ypos: case Channel::Yrot: return 1;
    default: return 2;
  }
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

bool parse_channel(std::string_view s, Channel& out) {
  static const std::array<std::pair<const char*, Channel>, 6> names = {{{"Xposition", Channel::Xpos},
                                                                        {"Yposition", Channel::Ypos},
                                                                        {"Zposition", Channel::Zpos},
                                                                        {"Xrotation", Channel::Xrot},
                                                                        {"Yrotation", Channel::Yrot},
                                                                        {"Zrotation", Channel::Zrot}}};
  for (const auto& [name, ch] : names)
    if (iequals(s, name)) {
      out = ch;
      return true;
    }
  return false;
}

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

struct Token {
  std::string_view text;
  int line = 0;
};

// Splits the HIERARCHY part into words and braces, tracking line numbers. Newlines are ordinary
// whitespace there (some files put '{' on the keyword's line, some do not indent at all).
class Lexer {
 public:
  explicit Lexer(std::string_view text) : text_(text) {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;  // UTF-8 byte-order mark
  }

  Token next() {
    skip_space();
    if (pos_ >= text_.size()) return {{}, last_line_};  // end of file: report the last line with content
    last_line_ = line_;
    const size_t start = pos_;
    if (text_[pos_] == '{' || text_[pos_] == '}') return {text_.substr(pos_++, 1), line_};
    while (pos_ < text_.size() && !is_blank(text_[pos_]) && text_[pos_] != '\n' && text_[pos_] != '{' &&
           text_[pos_] != '}')
      ++pos_;
    return {text_.substr(start, pos_ - start), line_};
  }

  // The rest of the current line up to a '{' (which stays for next()), trimmed: a joint's name, which
  // may contain spaces.
  Token rest_of_line() {
    while (pos_ < text_.size() && is_blank(text_[pos_])) ++pos_;
    const size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != '\n' && text_[pos_] != '{' && text_[pos_] != '}') ++pos_;
    size_t end = pos_;
    while (end > start && is_blank(text_[end - 1])) --end;
    return {text_.substr(start, end - start), line_};
  }

  size_t position() const { return pos_; }
  int line() const { return line_; }

 private:
  void skip_space() {
    while (pos_ < text_.size() && (is_blank(text_[pos_]) || text_[pos_] == '\n')) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }
  std::string_view text_;
  size_t pos_ = 0;
  int line_ = 1;
  int last_line_ = 1;
};

// A finite decimal number in the C locale's syntax, whatever the process locale.
bool parse_double(std::string_view s, double& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), out, std::chars_format::general);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

struct ParsedJoint {
  std::vector<Channel> channels;
  int first_column = 0;
  int line = 0;  // of the JOINT/ROOT keyword
  bool has_offset = false;
  bool has_channels = false;
};

class Parser {
 public:
  Parser(std::string_view text, std::string source, const BvhReadOptions& options)
      : text_(text), source_(std::move(source)), options_(options), lex_(text) {}

  Clip parse() {
    auto skeleton = std::make_shared<Skeleton>();
    parse_hierarchy(*skeleton);
    Clip clip;
    clip.name = stem(source_);
    parse_motion(*skeleton, clip);
    try {
      skeleton->validate();
    } catch (const std::invalid_argument& e) {
      throw InputError(source_, e.what());
    }
    clip.skeleton = std::move(skeleton);
    make_hemisphere_continuous(clip);
    return clip;
  }

 private:
  [[noreturn]] void fail(int line, const std::string& message) const { throw InputError(source_, line, message); }

  static std::string stem(const std::string& path) {
    const size_t slash = path.find_last_of("/\\");
    std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    const size_t dot = name.rfind('.');
    if (dot != std::string::npos && dot > 0) name.resize(dot);
    return name;
  }

  double number(const Token& t, const char* what) {
    if (t.text.empty()) fail(t.line, std::string("unexpected end of file: expected ") + what);
    double v = 0;
    if (!parse_double(t.text, v)) {
      const bool comma = t.text.find(',') != std::string_view::npos;
      fail(t.line, "'" + std::string(t.text) + "' is not a number (expected " + what + ")" +
                       (comma ? "; the decimal separator must be '.'" : ""));
    }
    if (!std::isfinite(v)) fail(t.line, "'" + std::string(t.text) + "' is not a finite number (" + what + ")");
    return v;
  }

  void expect(const Token& t, std::string_view word, const std::string& context) {
    if (t.text.empty()) fail(t.line, "unexpected end of file: expected '" + std::string(word) + "' " + context);
    if (t.text != word) fail(t.line, "expected '" + std::string(word) + "' " + context + ", found '" + std::string(t.text) + "'");
  }

  static std::string short_number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
  }

  // A position or offset in metres: refused if its size is past kMaxLength.
  void check_length(const glm::dvec3& metres, int line, const std::string& what) const {
    for (int k = 0; k < 3; ++k)
      if (!(std::abs(metres[k]) <= kMaxLength))
        fail(line, what + " is " + short_number(metres[k]) + " m after unit scaling: more than the 1e6 m a length may be");
  }

  glm::vec3 offset_vector() {
    glm::dvec3 v;
    int line = 0;
    for (int k = 0; k < 3; ++k) {
      const Token t = lex_.next();
      v[k] = number(t, "an OFFSET coordinate");
      line = t.line;
    }
    last_offset_ = v * static_cast<double>(options_.unit_scale);
    check_length(last_offset_, line, "the OFFSET");
    return glm::vec3(last_offset_);
  }

  void parse_hierarchy(Skeleton& skeleton) {
    const Token first = lex_.next();
    if (first.text.empty()) fail(first.line, "empty file: expected 'HIERARCHY'");
    if (first.text != "HIERARCHY") fail(first.line, "expected 'HIERARCHY' at the start of a BVH file, found '" + std::string(first.text) + "'");
    const Token root = lex_.next();
    expect(root, "ROOT", "after HIERARCHY");
    open_joint(skeleton, -1, root.line);

    std::vector<int> stack = {0};
    int columns = 0;
    while (!stack.empty()) {
      const int current = stack.back();
      Joint& joint = skeleton.joints[static_cast<size_t>(current)];
      ParsedJoint& info = parsed_[static_cast<size_t>(current)];
      const Token t = lex_.next();
      if (t.text.empty()) fail(t.line, "unexpected end of file: joint '" + joint.name + "' (line " + std::to_string(info.line) + ") is not closed with '}'");
      if (t.text == "OFFSET") {
        if (info.has_offset) fail(t.line, "joint '" + joint.name + "' has a second OFFSET");
        joint.offset = offset_vector();
        if (current == 0) root_offset_ = last_offset_;
        info.has_offset = true;
      } else if (t.text == "CHANNELS") {
        if (info.has_channels) fail(t.line, "joint '" + joint.name + "' has a second CHANNELS line");
        const Token count = lex_.next();
        const double n = number(count, "the channel count");
        if (n < 0 || n > 6 || n != std::floor(n)) fail(count.line, "channel count must be an integer from 0 to 6, found '" + std::string(count.text) + "'");
        bool seen[6] = {};
        for (int k = 0; k < static_cast<int>(n); ++k) {
          const Token c = lex_.next();
          Channel ch;
          if (c.text.empty()) fail(c.line, "unexpected end of file in the CHANNELS of joint '" + joint.name + "'");
          if (!parse_channel(c.text, ch))
            fail(c.line, "unknown channel '" + std::string(c.text) + "' for joint '" + joint.name + "' (expected Xposition..Zrotation; CHANNELS says " + std::string(count.text) + ")");
          if (seen[static_cast<int>(ch)]) fail(c.line, "channel '" + std::string(c.text) + "' repeats in joint '" + joint.name + "'");
          seen[static_cast<int>(ch)] = true;
          info.channels.push_back(ch);
        }
        info.has_channels = true;
        info.first_column = columns;
        columns += static_cast<int>(n);
      } else if (t.text == "JOINT") {
        if (!info.has_offset) fail(t.line, "joint '" + joint.name + "' has no OFFSET before its children");
        open_joint(skeleton, current, t.line);
        stack.push_back(skeleton.size() - 1);
      } else if (t.text == "End") {
        expect(lex_.next(), "Site", "after 'End'");
        if (joint.has_end_site) fail(t.line, "joint '" + joint.name + "' has a second End Site");
        expect(lex_.next(), "{", "to open the End Site of '" + joint.name + "'");
        expect(lex_.next(), "OFFSET", "in the End Site of '" + joint.name + "'");
        joint.end_site = offset_vector();
        joint.has_end_site = true;
        expect(lex_.next(), "}", "to close the End Site of '" + joint.name + "'");
      } else if (t.text == "}") {
        if (!info.has_offset) fail(t.line, "joint '" + joint.name + "' has no OFFSET");
        stack.pop_back();
      } else if (t.text == "ROOT" || t.text == "MOTION") {
        fail(t.line, "'" + std::string(t.text) + "' inside joint '" + joint.name + "': a '}' is missing");
      } else {
        fail(t.line, "unknown keyword '" + std::string(t.text) + "' in joint '" + joint.name + "' (expected OFFSET, CHANNELS, JOINT, End Site or '}')");
      }
    }
    total_columns_ = columns;
    if (total_columns_ == 0) fail(parsed_[0].line, "the hierarchy has no channels");

    const Token motion = lex_.next();
    if (motion.text.empty()) fail(motion.line, "missing MOTION section after the hierarchy");
    if (motion.text == "ROOT") fail(motion.line, "a second ROOT: only one skeleton per file is supported");
    if (motion.text != "MOTION") fail(motion.line, "expected 'MOTION' after the hierarchy, found '" + std::string(motion.text) + "'");
    motion_end_ = lex_.position();
    motion_line_ = lex_.line();
  }

  void open_joint(Skeleton& skeleton, int parent, int keyword_line) {
    const Token name = lex_.rest_of_line();
    if (name.text.empty()) fail(keyword_line, "joint without a name");
    expect(lex_.next(), "{", "after joint '" + std::string(name.text) + "'");
    Joint j;
    j.name = std::string(name.text);
    j.parent = parent;
    if (!names_.insert(j.name).second) fail(keyword_line, "joint name '" + j.name + "' repeats");
    skeleton.joints.push_back(std::move(j));
    ParsedJoint info;
    info.line = keyword_line;
    parsed_.push_back(std::move(info));
  }

  // One line of the MOTION part: its whitespace-separated words.
  struct Line {
    std::vector<std::string_view> words;
    int number = 0;
  };

  bool next_line(size_t& pos, int& line_no, Line& out) {
    while (pos < text_.size()) {
      const size_t end = std::min(text_.find('\n', pos), text_.size());
      out.words.clear();
      out.number = line_no;
      size_t i = pos;
      while (i < end) {
        while (i < end && is_blank(text_[i])) ++i;
        const size_t s = i;
        while (i < end && !is_blank(text_[i])) ++i;
        if (i > s) out.words.push_back(text_.substr(s, i - s));
      }
      pos = end + 1;
      ++line_no;
      if (!out.words.empty()) {
        last_content_line_ = out.number;
        return true;
      }
    }
    return false;
  }

  void parse_motion(Skeleton& skeleton, Clip& clip) {
    size_t pos = motion_end_;
    int line_no = motion_line_;
    last_content_line_ = motion_line_;
    // The rest of the MOTION keyword's line must be empty.
    {
      const size_t end = std::min(text_.find('\n', pos), text_.size());
      for (size_t i = pos; i < end; ++i)
        if (!is_blank(text_[i])) fail(line_no, "unexpected text after 'MOTION'");
      pos = end + 1;
      ++line_no;
    }
    Line line;
    // "Frames: N"
    if (!next_line(pos, line_no, line)) fail(last_content_line_, "unexpected end of file: expected 'Frames:' after MOTION");
    std::vector<std::string_view> w = line.words;
    if (w.size() >= 2 && w[0] == "Frames" && w[1] == ":") w.erase(w.begin() + 1);
    if (w.empty() || w[0] != "Frames:" || w.size() != 2)
      fail(line.number, "expected 'Frames: N' after MOTION, found '" + std::string(line.words[0]) + "'");
    unsigned long long declared = 0;
    {
      const auto r = std::from_chars(w[1].data(), w[1].data() + w[1].size(), declared);
      if (r.ec == std::errc::result_out_of_range) fail(line.number, "frame count '" + std::string(w[1]) + "' is out of range");
      if (r.ec != std::errc() || r.ptr != w[1].data() + w[1].size())
        fail(line.number, "frame count '" + std::string(w[1]) + "' is not a non-negative integer");
    }
    const int frames_line = line.number;
    // "Frame Time: t"
    if (!next_line(pos, line_no, line)) fail(last_content_line_, "unexpected end of file: expected 'Frame Time:'");
    w = line.words;
    if (w.size() >= 3 && w[0] == "Frame" && w[1] == "Time" && w[2] == ":") w.erase(w.begin() + 2);
    if (w.size() != 3 || w[0] != "Frame" || w[1] != "Time:")
      fail(line.number, "expected 'Frame Time: seconds', found '" + std::string(line.words[0]) + "'");
    const double frame_time = number({w[2], line.number}, "the frame time in seconds");
    if (!(frame_time > 0)) fail(line.number, "frame time must be positive, found '" + std::string(w[2]) + "'");
    if (frame_time < kMinFrameTime || frame_time > kMaxFrameTime)
      fail(line.number, "frame time '" + std::string(w[2]) + "' is outside 1e-05 to 10000 seconds");
    clip.fps = static_cast<float>(1.0 / frame_time);

    // Never trust the declared count for memory: each value takes at least two bytes ("0 ").
    const size_t bytes_left = text_.size() > pos ? text_.size() - pos : 0;
    const size_t by_size = bytes_left / (2 * static_cast<size_t>(total_columns_)) + 1;
    clip.frames.reserve(static_cast<size_t>(std::min<unsigned long long>(declared, by_size)));

    const int n = skeleton.size();
    const double scale = options_.unit_scale;
    // Non-root position channels: the first frame's values, and the first line where they change.
    std::vector<glm::dvec3> joint_translation(static_cast<size_t>(n), glm::dvec3(0));
    std::vector<bool> joint_translates(static_cast<size_t>(n), false);
    std::vector<int> changed_at(static_cast<size_t>(n), 0);
    for (int j = 1; j < n; ++j)
      for (Channel c : parsed_[static_cast<size_t>(j)].channels)
        if (is_position(c)) joint_translates[static_cast<size_t>(j)] = true;

    std::vector<double> values(static_cast<size_t>(total_columns_));
    while (next_line(pos, line_no, line)) {
      if (line.words.size() != static_cast<size_t>(total_columns_))
        fail(line.number, "frame " + std::to_string(clip.frames.size()) + " has " + std::to_string(line.words.size()) +
                              " values, but the hierarchy declares " + std::to_string(total_columns_) + " channels");
      for (size_t k = 0; k < values.size(); ++k) values[k] = number({line.words[k], line.number}, "a channel value");
      Pose pose(n);
      for (int j = 0; j < n; ++j) {
        const ParsedJoint& info = parsed_[static_cast<size_t>(j)];
        glm::dquat q(1, 0, 0, 0);
        glm::dvec3 translation(0);
        for (size_t k = 0; k < info.channels.size(); ++k) {
          const Channel c = info.channels[k];
          const double v = values[static_cast<size_t>(info.first_column) + k];
          if (is_position(c)) {
            translation[axis_of(c)] = v;
          } else {
            glm::dvec3 axis(0);
            axis[axis_of(c)] = 1;
            q = q * glm::angleAxis(glm::radians(v), axis);  // channels compose in the order listed
          }
        }
        pose.rotations[static_cast<size_t>(j)] = without_negligible_components(glm::normalize(q));
        if (j == 0) {
          const glm::dvec3 root = root_offset_ + translation * scale;
          check_length(root, line.number, "the root position of frame " + std::to_string(clip.frames.size()));
          pose.root_position = glm::vec3(root);
        } else if (joint_translates[static_cast<size_t>(j)]) {
          glm::dvec3& first = joint_translation[static_cast<size_t>(j)];
          if (clip.frames.empty()) {
            first = translation;
          } else if (changed_at[static_cast<size_t>(j)] == 0) {
            const double tol = 1e-4 * std::max({1.0, glm::length(first), glm::length(translation)});
            if (glm::length(translation - first) > tol) changed_at[static_cast<size_t>(j)] = line.number;
          }
        }
      }
      clip.frames.push_back(std::move(pose));
    }
    if (clip.frames.empty()) fail(last_content_line_, "the MOTION section has no frames");
    if (declared != clip.frames.size() && options_.warnings)
      options_.warnings->push_back(source_ + ":" + std::to_string(frames_line) + ": 'Frames: " + std::to_string(declared) +
                                   "' but the file holds " + std::to_string(clip.frames.size()) + " frames; using " +
                                   std::to_string(clip.frames.size()));

    for (int j = 1; j < n; ++j) {
      if (!joint_translates[static_cast<size_t>(j)]) continue;
      Joint& joint = skeleton.joints[static_cast<size_t>(j)];
      if (changed_at[static_cast<size_t>(j)] != 0)
        fail(changed_at[static_cast<size_t>(j)], "the position channels of joint '" + joint.name +
                                                     "' change over the clip: only the root may translate");
      const glm::dvec3 offset = glm::dvec3(joint.offset) / scale;
      const glm::dvec3 value = joint_translation[static_cast<size_t>(j)];
      const double tol = 1e-4 * std::max({1.0, glm::length(offset), glm::length(value)});
      const bool restates = glm::length(value - offset) <= tol;
      if (!restates) {
        check_length((offset + value) * scale, parsed_[static_cast<size_t>(j)].line,
                     "the OFFSET of joint '" + joint.name + "' plus its position channels");
        joint.offset = glm::vec3((offset + value) * scale);
      }
      if (options_.warnings)
        options_.warnings->push_back(source_ + ":" + std::to_string(parsed_[static_cast<size_t>(j)].line) +
                                     ": constant position channels of joint '" + joint.name + "' " +
                                     (restates ? "restate its OFFSET" : "were added to its OFFSET"));
    }
    skeleton.joints[0].offset = glm::vec3(0.0f);  // folded into root_position
  }

  std::string_view text_;
  std::string source_;
  const BvhReadOptions& options_;
  Lexer lex_;
  std::vector<ParsedJoint> parsed_;
  std::unordered_set<std::string> names_;  // a hash set: files with very many joints stay linear
  int total_columns_ = 0;
  glm::dvec3 last_offset_{0.0};
  glm::dvec3 root_offset_{0.0};  // metres, kept in double until it is added to the root's position
  size_t motion_end_ = 0;
  int motion_line_ = 0;
  int last_content_line_ = 0;
};

// Shortest text that reads back as the same float, independent of the locale.
void append_number(std::string& out, float v) {
  if (v == 0.0f) v = 0.0f;  // no "-0"
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

void append_number(std::string& out, double v) {
  char buf[40];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

// Euler angles (degrees) with R = Rz(z) · Rx(x) · Ry(y), the order the writer declares.
glm::dvec3 euler_zxy_degrees(const glm::quat& qf) {
  const glm::dmat3 m = glm::mat3_cast(glm::normalize(glm::dquat(qf)));
  // glm matrices are column-major: m[col][row]. With c = cos, s = sin:
  //   row 2 = (-cx·sy, sx, cx·cy), column 1 = (-sz·cx, cz·cx, sx).
  const double sx = std::clamp(m[1][2], -1.0, 1.0);
  double x = std::asin(sx), y, z;
  if (std::abs(sx) < 0.9999999) {
    z = std::atan2(-m[1][0], m[1][1]);
    y = std::atan2(-m[0][2], m[2][2]);
  } else {  // gimbal lock: only z ± y is defined; put it all in z
    y = 0;
    z = std::atan2(m[0][1], m[0][0]);
  }
  return glm::degrees(glm::dvec3(x, y, z));
}

// The hierarchy, depth-first with an explicit stack (no recursion, whatever the depth). Indentation is
// capped so that a very deep chain does not grow the file quadratically.
void write_hierarchy(std::string& out, const Skeleton& skeleton, const std::vector<std::vector<int>>& children,
                     double inv_scale, std::vector<int>& order) {
  struct Item {
    int joint;
    int depth;
    bool closing;
  };
  auto vec = [&](const glm::vec3& v) {
    for (int k = 0; k < 3; ++k) {
      append_number(out, v[k]);
      out += k < 2 ? " " : "\n";
    }
  };
  std::vector<Item> stack = {{0, 0, false}};
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    const Joint& joint = skeleton.joints[static_cast<size_t>(item.joint)];
    const std::string indent(static_cast<size_t>(std::min(item.depth, 32)), '\t');
    if (item.closing) {
      if (joint.has_end_site) {
        out += indent + "\tEnd Site\n" + indent + "\t{\n" + indent + "\t\tOFFSET ";
        vec(glm::vec3(glm::dvec3(joint.end_site) * inv_scale));
        out += indent + "\t}\n";
      }
      out += indent + "}\n";
      continue;
    }
    order.push_back(item.joint);
    out += indent + (item.joint == 0 ? "ROOT " : "JOINT ") + joint.name + "\n" + indent + "{\n";
    out += indent + "\tOFFSET ";
    vec(item.joint == 0 ? glm::vec3(0.0f) : glm::vec3(glm::dvec3(joint.offset) * inv_scale));  // root: in the motion
    out += indent + (item.joint == 0 ? "\tCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
                                     : "\tCHANNELS 3 Zrotation Xrotation Yrotation\n");
    stack.push_back({item.joint, item.depth, true});
    const auto& kids = children[static_cast<size_t>(item.joint)];
    for (auto it = kids.rbegin(); it != kids.rend(); ++it) stack.push_back({*it, item.depth + 1, false});
  }
}

}  // namespace

Clip parse_bvh(const std::string& text, const std::string& source_name, const BvhReadOptions& options) {
  if (!(options.unit_scale > 0.0f) || !std::isfinite(options.unit_scale))
    throw InputError(source_name, "unit scale must be a positive number");
  return Parser(text, source_name, options).parse();
}

Clip read_bvh(const std::string& path, const BvhReadOptions& options) {
  return parse_bvh(read_file(path), path, options);
}

std::string format_bvh(const Clip& clip, const BvhWriteOptions& options) {
  if (!clip.skeleton || clip.skeleton->joints.empty()) throw std::invalid_argument("format_bvh: clip '" + clip.name + "' has no skeleton");
  if (!(options.unit_scale > 0.0f)) throw std::invalid_argument("format_bvh: unit scale must be positive");
  if (!(clip.fps > 0.0f)) throw std::invalid_argument("format_bvh: clip '" + clip.name + "' has no frame rate");
  const Skeleton& skeleton = *clip.skeleton;
  skeleton.validate();
  const int n = skeleton.size();
  std::vector<std::vector<int>> children(static_cast<size_t>(n));
  for (int j = 1; j < n; ++j) children[static_cast<size_t>(skeleton.joints[static_cast<size_t>(j)].parent)].push_back(j);
  const double inv_scale = 1.0 / static_cast<double>(options.unit_scale);

  std::string out = "HIERARCHY\n";
  std::vector<int> order;  // depth-first, the order the channels are written in
  write_hierarchy(out, skeleton, children, inv_scale, order);
  out += "MOTION\nFrames: " + std::to_string(clip.frames.size()) + "\nFrame Time: ";
  append_number(out, 1.0 / static_cast<double>(clip.fps));
  out += "\n";
  for (size_t f = 0; f < clip.frames.size(); ++f) {
    const Pose& pose = clip.frames[f];
    if (pose.rotations.size() != static_cast<size_t>(n))
      throw std::invalid_argument("format_bvh: frame " + std::to_string(f) + " of clip '" + clip.name + "' has " +
                                  std::to_string(pose.rotations.size()) + " rotations for " + std::to_string(n) + " joints");
    const glm::vec3 p = glm::vec3(glm::dvec3(pose.root_position) * inv_scale);
    for (int k = 0; k < 3; ++k) {
      append_number(out, p[k]);
      out += ' ';
    }
    for (size_t i = 0; i < order.size(); ++i) {
      const glm::dvec3 e = euler_zxy_degrees(pose.rotations[static_cast<size_t>(order[i])]);
      append_number(out, static_cast<float>(e.z));
      out += ' ';
      append_number(out, static_cast<float>(e.x));
      out += ' ';
      append_number(out, static_cast<float>(e.y));
      out += i + 1 < order.size() ? ' ' : '\n';
    }
  }
  return out;
}

void write_bvh(const Clip& clip, const std::string& path, const BvhWriteOptions& options) {
  write_file_atomic(path, format_bvh(clip, options));
}

}  // namespace prep
