#include <doctest/doctest.h>

#include <algorithm>
#include <clocale>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/motion/bvh.h"
#include "engine/motion/kinematics.h"
#include "engine/util/error.h"
#include "tests/support/paths.h"

using namespace prep;
namespace fs = std::filesystem;

namespace {

// Unit scale of each mocap folder (see ../shared/mocap/README.md).
float folder_unit_scale(const std::string& folder) { return folder == "cmu31" ? 0.05644f : 0.01f; }

struct WorldPose {
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
};

WorldPose world(const Clip& clip, int frame) {
  WorldPose w;
  forward_kinematics(*clip.skeleton, clip.frames[static_cast<size_t>(frame)], w.positions, &w.rotations);
  return w;
}

// Largest difference over every frame and joint: world positions (metres), end sites, and world rotations
// up to sign (quaternion components).
struct Difference {
  double position = 0;
  double rotation = 0;
};

Difference compare_clips(const Clip& a, const Clip& b) {
  Difference d;
  REQUIRE(a.skeleton->size() == b.skeleton->size());
  REQUIRE(a.frame_count() == b.frame_count());
  for (int j = 0; j < a.skeleton->size(); ++j) {
    REQUIRE(a.skeleton->joints[static_cast<size_t>(j)].name == b.skeleton->joints[static_cast<size_t>(j)].name);
    REQUIRE(a.skeleton->joints[static_cast<size_t>(j)].has_end_site == b.skeleton->joints[static_cast<size_t>(j)].has_end_site);
  }
  for (int f = 0; f < a.frame_count(); ++f) {
    const WorldPose wa = world(a, f), wb = world(b, f);
    for (int j = 0; j < a.skeleton->size(); ++j) {
      const size_t k = static_cast<size_t>(j);
      d.position = std::max(d.position, static_cast<double>(glm::length(wa.positions[k] - wb.positions[k])));
      if (a.skeleton->joints[k].has_end_site) {
        const glm::vec3 ea = end_site_position(*a.skeleton, j, wa.positions, wa.rotations);
        const glm::vec3 eb = end_site_position(*b.skeleton, j, wb.positions, wb.rotations);
        d.position = std::max(d.position, static_cast<double>(glm::length(ea - eb)));
      }
      const glm::quat qa = wa.rotations[k], qb = wb.rotations[k];
      const glm::vec4 plus(qa.x - qb.x, qa.y - qb.y, qa.z - qb.z, qa.w - qb.w);
      const glm::vec4 minus(qa.x + qb.x, qa.y + qb.y, qa.z + qb.z, qa.w + qb.w);
      const float up_to_sign = std::min(glm::length(plus), glm::length(minus));
      d.rotation = std::max(d.rotation, static_cast<double>(up_to_sign));
    }
  }
  return d;
}

std::vector<fs::path> mocap_files() {
  std::vector<fs::path> files;
  for (const auto& folder : fs::directory_iterator(test::mocap()))
    if (folder.is_directory())
      for (const auto& f : fs::directory_iterator(folder.path()))
        if (f.path().extension() == ".bvh") files.push_back(f.path());
  std::sort(files.begin(), files.end());
  return files;
}

// A small valid file; the malformed cases below edit one line of it (line numbers in the comments).
const char* const kSmall =
    "HIERARCHY\n"                                                          // 1
    "ROOT hips\n"                                                          // 2
    "{\n"                                                                  // 3
    "  OFFSET 0 0 0\n"                                                     // 4
    "  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"  // 5
    "  JOINT leg\n"                                                        // 6
    "  {\n"                                                                // 7
    "    OFFSET 0 -10 0\n"                                                 // 8
    "    CHANNELS 3 Zrotation Xrotation Yrotation\n"                      // 9
    "    End Site\n"                                                       // 10
    "    {\n"                                                              // 11
    "      OFFSET 0 -10 0\n"                                               // 12
    "    }\n"                                                              // 13
    "  }\n"                                                                // 14
    "}\n"                                                                  // 15
    "MOTION\n"                                                             // 16
    "Frames: 2\n"                                                          // 17
    "Frame Time: 0.5\n"                                                    // 18
    "0 100 0 0 0 0 90 0 0\n"                                               // 19
    "1.5 100 0 0 0 0 45 0 0\n";                                            // 20

std::string replace_line(const std::string& text, int line, const std::string& with) {
  std::string out;
  int n = 1;
  size_t pos = 0;
  while (pos < text.size()) {
    const size_t end = text.find('\n', pos);
    const std::string current = text.substr(pos, end - pos);
    out += (n == line ? with : current) + "\n";
    ++n;
    pos = end == std::string::npos ? text.size() : end + 1;
  }
  return out;
}

std::string first_lines(const std::string& text, int lines) {
  size_t pos = 0;
  for (int i = 0; i < lines; ++i) pos = text.find('\n', pos) + 1;
  return text.substr(0, pos);
}

}  // namespace

TEST_CASE("every BVH in ../shared/mocap survives import -> export -> import within 1e-5") {
  const auto files = mocap_files();
  REQUIRE(files.size() >= 24);  // 18 daz43 + 6 cmu31 clips
  for (const auto& path : files) {
    CAPTURE(path.string());
    BvhReadOptions in;
    in.unit_scale = folder_unit_scale(path.parent_path().filename().string());
    const Clip original = read_bvh(path.string(), in);
    BvhWriteOptions out;
    out.unit_scale = in.unit_scale;
    const Clip again = parse_bvh(format_bvh(original, out), path.filename().string(), in);
    CHECK(again.fps == doctest::Approx(original.fps).epsilon(1e-6));
    const Difference d = compare_clips(original, again);
    CHECK(d.position < 1e-5);
    CHECK(d.rotation < 1e-5);
  }
}

TEST_CASE("write_bvh writes a file that read_bvh reads back") {
  const Clip clip = parse_bvh(kSmall, "small.bvh");
  fs::create_directories(test::tmp_dir());
  const std::string path = test::tmp_dir() + "/bvh_test_small.bvh";
  write_bvh(clip, path);
  const Clip back = read_bvh(path);
  CHECK(back.name == "bvh_test_small");
  const Difference d = compare_clips(clip, back);
  CHECK(d.position < 1e-6);
  fs::remove(path);
}

TEST_CASE("the small BVH loads with the hand-computed pose") {
  std::vector<std::string> warnings;
  BvhReadOptions options;
  options.warnings = &warnings;
  const Clip clip = parse_bvh(kSmall, "small.bvh", options);
  CHECK(warnings.empty());
  CHECK(clip.name == "small");
  CHECK(clip.fps == doctest::Approx(2.0));
  REQUIRE(clip.frame_count() == 2);
  REQUIRE(clip.skeleton->size() == 2);
  CHECK(clip.skeleton->joints[1].has_end_site);
  // Frame 0: hips at (0, 1, 0) m; leg rotated 90 deg about Z, so its End Site (0,-0.1,0) points to +X.
  const WorldPose w = world(clip, 0);
  CHECK(w.positions[1].y == doctest::Approx(0.9));
  const glm::vec3 toe = end_site_position(*clip.skeleton, 1, w.positions, w.rotations);
  CHECK(toe.x == doctest::Approx(0.1));
  CHECK(toe.y == doctest::Approx(0.9));
  // Frame 1: hips at x = 1.5 cm; 45 deg.
  const WorldPose w1 = world(clip, 1);
  const glm::vec3 toe1 = end_site_position(*clip.skeleton, 1, w1.positions, w1.rotations);
  CHECK(toe1.x == doctest::Approx(0.015 + 0.1 * std::sqrt(0.5)));
  CHECK(toe1.y == doctest::Approx(0.9 - 0.1 * std::sqrt(0.5)));
}

TEST_CASE("BVH text with CRLF, tabs, no indentation, exponents and '{' on the keyword line loads") {
  const std::string text =
      "HIERARCHY\r\nROOT  hips {\r\n\tOFFSET\t1e1 0 0\r\nCHANNELS 6 Xposition Yposition Zposition Yrotation Xrotation Zrotation\r\n"
      "JOINT upper leg\r\n{\r\nOFFSET 0 -1.0E+1 +0\r\nCHANNELS 3 Xrotation Yrotation Zrotation\r\n}\r\n}\r\n"
      "MOTION\r\nFrames:\t1\r\nFrame Time:\t3.33333e-02\r\n\t2.5e0 1.0e2 0 0 0 0 0 0 9e1\r\n";
  const Clip clip = parse_bvh(text, "crlf.bvh");
  REQUIRE(clip.skeleton->size() == 2);
  CHECK(clip.skeleton->joints[1].name == "upper leg");
  CHECK(clip.fps == doctest::Approx(30.0).epsilon(1e-4));
  // Root OFFSET (10 cm) folds into the root position with the 2.5 cm channel.
  CHECK(clip.frames[0].root_position.x == doctest::Approx(0.125));
  CHECK(clip.skeleton->joints[0].offset == glm::vec3(0.0f));
  const WorldPose w = world(clip, 0);
  CHECK(w.positions[1].x == doctest::Approx(0.125));
  CHECK(w.positions[1].y == doctest::Approx(0.9));
}

namespace {
bool has_subnormal_component(const glm::quat& q) {
  for (int c = 0; c < 4; ++c)
    if (std::fpclassify(q[c]) == FP_SUBNORMAL) return true;
  return false;
}
}  // namespace

TEST_CASE("channels a converter left at 1e-16 degrees load as exact zeros, not subnormal floats") {
  // A 1e-16 degree turn about X then 2e-18 about Y gives quaternion components near 1e-39 as floats:
  // subnormal numbers, each product with which costs a microcode assist on x86.
  const std::string text =
      "HIERARCHY\nROOT hips\n{\nOFFSET 0 0 0\nCHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation\n"
      "JOINT leg\n{\nOFFSET 0 -10 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{\nOFFSET 0 -10 0\n}\n}\n}\n"
      "MOTION\nFrames: 2\nFrame Time: 0.0333333\n"
      "0 100 0 0 -3.4e-21 -7e-37 1e-16 2e-18 0\n"
      "0 100 0 30 -3.4e-21 -7e-37 40 2e-18 25\n";
  BvhReadOptions options;
  options.unit_scale = 0.01f;
  const Clip clip = parse_bvh(text, "noise.bvh", options);
  REQUIRE(clip.frame_count() == 2);
  for (const Pose& pose : clip.frames)
    for (const glm::quat& q : pose.rotations) CHECK_FALSE(has_subnormal_component(q));
  CHECK(clip.frames[0].rotations[0] == glm::quat(1, 0, 0, 0));
  CHECK(clip.frames[0].rotations[1] == glm::quat(1, 0, 0, 0));
  // A real rotation keeps every bit: the leg's Z 1e-16 X 2e-18 Y 0 becomes the identity, but Z 40 X 2e-18
  // Y 25 is the product of two real turns, its tiny X component (about 1e-20) dropped.
  const glm::dquat z(glm::angleAxis(glm::radians(40.0), glm::dvec3(0, 0, 1)));
  const glm::dquat y(glm::angleAxis(glm::radians(25.0), glm::dvec3(0, 1, 0)));
  const glm::dquat expected = glm::normalize(z * y);
  const glm::quat leg = clip.frames[1].rotations[1];
  CHECK(leg.w == static_cast<float>(expected.w));
  CHECK(leg.y == static_cast<float>(expected.y));
  CHECK(leg.z == static_cast<float>(expected.z));
  CHECK(std::abs(leg.x - static_cast<float>(expected.x)) < 1e-9f);
  CHECK(clip.frames[1].rotations[0] == glm::quat(glm::angleAxis(glm::radians(30.0), glm::dvec3(0, 0, 1))));
}

TEST_CASE("no clip in ../shared/mocap loads with a subnormal rotation component") {
  const auto files = mocap_files();
  REQUIRE(files.size() >= 24);
  for (const auto& path : files) {
    CAPTURE(path.string());
    const Clip clip = read_bvh(path.string());
    int subnormal = 0;
    for (const Pose& pose : clip.frames)
      for (const glm::quat& q : pose.rotations) subnormal += has_subnormal_component(q) ? 1 : 0;
    CHECK(subnormal == 0);
  }
}

TEST_CASE("a CMU clip with mixed rotation orders loads with the pose derived by hand from the file") {
  // punch_right_14_01.bvh, frame 0 (line 188). The chain from the root to LeftElbow, with the OFFSETs of
  // lines 4-105 and the channel values of frame 0 (columns 0-5, 36-44, 54-59), in CMU units:
  //   Hips         CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation
  //   lowerback, Chest, Chest2, LeftCollar: Zrotation Yrotation Xrotation
  //   LeftShoulder: Zrotation Xrotation Yrotation  (the other order in the same file)
  struct M3 {  // row-major 3x3, double
    double m[3][3];
    M3 operator*(const M3& o) const {
      M3 r{};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          for (int k = 0; k < 3; ++k) r.m[i][j] += m[i][k] * o.m[k][j];
      return r;
    }
    glm::dvec3 operator*(const glm::dvec3& v) const {
      return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
              m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
  };
  const double deg = 3.14159265358979323846 / 180.0;
  auto rx = [&](double a) { a *= deg; return M3{{{1, 0, 0}, {0, std::cos(a), -std::sin(a)}, {0, std::sin(a), std::cos(a)}}}; };
  auto ry = [&](double a) { a *= deg; return M3{{{std::cos(a), 0, std::sin(a)}, {0, 1, 0}, {-std::sin(a), 0, std::cos(a)}}}; };
  auto rz = [&](double a) { a *= deg; return M3{{{std::cos(a), -std::sin(a), 0}, {std::sin(a), std::cos(a), 0}, {0, 0, 1}}}; };

  const glm::dvec3 hips_position(6.2765, 16.7068, -0.3117);
  const M3 hips = rz(2.3749) * ry(-43.8931) * rx(3.6866);
  const M3 lowerback = rz(-6.1556) * ry(-1.8148) * rx(10.1094);
  const M3 chest = rz(3.3747) * ry(-2.9652) * rx(0.9225);
  const M3 chest2 = rz(7.4460) * ry(-1.3491) * rx(-4.2102);
  const M3 collar = rz(0.0) * ry(0.0) * rx(0.0);
  const M3 shoulder_zxy = rz(2.6452) * rx(-13.1049) * ry(-39.5849);
  const M3 shoulder_zyx = rz(2.6452) * ry(-13.1049) * rx(-39.5849);  // the wrong reading, for contrast
  const glm::dvec3 chest_offset(-0.02108, 2.07573, -0.16981), chest2_offset(0.05070, 2.08439, -0.03141),
      shoulder_offset(3.52315, 0.73219, -0.54694), elbow_offset(0, -5.324620, 0);  // lowerback, collar: 0
  auto elbow = [&](const M3& shoulder) {
    const M3 r_chest2 = hips * lowerback * chest * chest2;
    const glm::dvec3 p_chest = hips_position + (hips * lowerback) * chest_offset;
    const glm::dvec3 p_chest2 = p_chest + (hips * lowerback * chest) * chest2_offset;
    const glm::dvec3 p_shoulder = p_chest2 + (r_chest2 * collar) * shoulder_offset;
    return p_shoulder + (r_chest2 * collar * shoulder) * elbow_offset;
  };
  const double unit = 0.05644;
  const glm::dvec3 expected = elbow(shoulder_zxy) * unit;
  const glm::dvec3 wrong = elbow(shoulder_zyx) * unit;
  REQUIRE(glm::length(expected - wrong) > 0.02);  // the rotation order matters by centimetres here

  BvhReadOptions options;
  options.unit_scale = static_cast<float>(unit);
  const Clip clip = read_bvh(test::mocap() + "/cmu31/punch_right_14_01.bvh", options);
  const Skeleton& s = *clip.skeleton;
  const int e = s.find("LeftElbow");
  REQUIRE(e >= 0);
  // The chain is the one written out above.
  const char* chain[] = {"LeftElbow", "LeftShoulder", "LeftCollar", "Chest2", "Chest", "lowerback", "Hips"};
  int j = e;
  for (const char* name : chain) {
    REQUIRE(j >= 0);
    CHECK(s.joints[static_cast<size_t>(j)].name == name);
    j = s.joints[static_cast<size_t>(j)].parent;
  }
  const WorldPose w = world(clip, 0);
  const glm::dvec3 got(w.positions[static_cast<size_t>(e)]);
  CHECK(glm::length(got - expected) < 1e-5);
}

TEST_CASE("a declared frame count that differs from the data warns and uses the rows that are there") {
  std::vector<std::string> warnings;
  BvhReadOptions options;
  options.warnings = &warnings;
  // Fewer rows than declared: 3 declared, 2 present.
  const Clip fewer = parse_bvh(replace_line(kSmall, 17, "Frames: 3"), "fewer.bvh", options);
  CHECK(fewer.frame_count() == 2);
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].find("fewer.bvh:17:") == 0);
  // More rows than declared.
  warnings.clear();
  const Clip more = parse_bvh(replace_line(kSmall, 17, "Frames: 1"), "more.bvh", options);
  CHECK(more.frame_count() == 2);
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].find("more.bvh:17:") == 0);
}

TEST_CASE("a huge declared Frames: is not allocated: the rows present are used, with a warning") {
  std::vector<std::string> warnings;
  BvhReadOptions options;
  options.warnings = &warnings;
  // 10^15 frames of 9 floats would be hundreds of petabytes: a blind reserve would throw or abort.
  const Clip clip = parse_bvh(replace_line(kSmall, 17, "Frames: 1000000000000000"), "huge.bvh", options);
  CHECK(clip.frame_count() == 2);
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].find("huge.bvh:17:") == 0);
  CHECK(clip.frames.capacity() < 100);
  // A count beyond any integer type is an error naming the line.
  CHECK_THROWS_WITH_AS(parse_bvh(replace_line(kSmall, 17, "Frames: 99999999999999999999999999"), "huge.bvh"),
                       doctest::Contains("huge.bvh:17: frame count"), InputError);
}

TEST_CASE("malformed BVH files give an error naming the file and the line") {
  SUBCASE("truncated inside the hierarchy") {
    CHECK_THROWS_WITH_AS(parse_bvh(first_lines(kSmall, 9), "cut.bvh"),
                         doctest::Contains("cut.bvh:9: unexpected end of file: joint 'leg'"), InputError);
  }
  SUBCASE("truncated inside a frame") {
    const std::string text(kSmall);
    CHECK_THROWS_WITH_AS(parse_bvh(text.substr(0, text.size() - 8), "cut.bvh"),
                         doctest::Contains("cut.bvh:20: frame 1 has 6 values, but the hierarchy declares 9 channels"),
                         InputError);
  }
  SUBCASE("truncated after the frame time") {
    CHECK_THROWS_WITH_AS(parse_bvh(first_lines(kSmall, 18), "cut.bvh"),
                         doctest::Contains("cut.bvh:18: the MOTION section has no frames"), InputError);
  }
  SUBCASE("wrong channel count in a row") {
    CHECK_THROWS_WITH_AS(parse_bvh(replace_line(kSmall, 19, "0 100 0 0 0 0 90 0 0 7"), "wide.bvh"),
                         doctest::Contains("wide.bvh:19: frame 0 has 10 values"), InputError);
  }
  SUBCASE("NaN and infinity") {
    CHECK_THROWS_WITH_AS(parse_bvh(replace_line(kSmall, 20, "1.5 100 0 0 nan 0 45 0 0"), "nan.bvh"),
                         doctest::Contains("nan.bvh:20: 'nan' is not a finite number"), InputError);
    CHECK_THROWS_WITH_AS(parse_bvh(replace_line(kSmall, 8, "    OFFSET 0 -inf 0"), "inf.bvh"),
                         doctest::Contains("inf.bvh:8: '-inf' is not a finite number"), InputError);
    CHECK_THROWS_WITH_AS(parse_bvh(replace_line(kSmall, 19, "0 1e999 0 0 0 0 90 0 0"), "big.bvh"),
                         doctest::Contains("big.bvh:19: '1e999' is not a number"), InputError);
  }
  SUBCASE("missing MOTION") {
    CHECK_THROWS_WITH_AS(parse_bvh(first_lines(kSmall, 15), "nomotion.bvh"),
                         doctest::Contains("nomotion.bvh:15: missing MOTION section"), InputError);
    CHECK_THROWS_WITH_AS(parse_bvh(replace_line(kSmall, 16, "MOTON"), "nomotion.bvh"),
                         doctest::Contains("nomotion.bvh:16: expected 'MOTION'"), InputError);
  }
  SUBCASE("unknown keyword") {
    CHECK_THROWS_WITH_AS(parse_bvh(replace_line(kSmall, 9, "    ROTATION 3 Zrotation Xrotation Yrotation"), "kw.bvh"),
                         doctest::Contains("kw.bvh:9: unknown keyword 'ROTATION' in joint 'leg'"), InputError);
    CHECK_THROWS_WITH_AS(parse_bvh(replace_line(kSmall, 9, "    CHANNELS 3 Zrotation Xrotation Wrotation"), "ch.bvh"),
                         doctest::Contains("ch.bvh:9: unknown channel 'Wrotation'"), InputError);
  }
  SUBCASE("not a BVH, or empty") {
    CHECK_THROWS_WITH_AS(parse_bvh("", "empty.bvh"), doctest::Contains("empty.bvh:1: empty file"), InputError);
    CHECK_THROWS_WITH_AS(parse_bvh("{\"a\": 1}", "json.bvh"), doctest::Contains("json.bvh:1: expected 'HIERARCHY'"),
                         InputError);
  }
  SUBCASE("frame time") {
    CHECK_THROWS_WITH_AS(parse_bvh(replace_line(kSmall, 18, "Frame Time: 0"), "ft.bvh"),
                         doctest::Contains("ft.bvh:18: frame time must be positive"), InputError);
  }
  SUBCASE("a non-root joint whose position channels change over the clip") {
    std::string text = replace_line(kSmall, 9, "    CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation");
    text = replace_line(text, 19, "0 100 0 0 0 0 0 -10 0 90 0 0");
    text = replace_line(text, 20, "0 100 0 0 0 0 0 -12 0 45 0 0");
    CHECK_THROWS_WITH_AS(parse_bvh(text, "stretch.bvh"),
                         doctest::Contains("stretch.bvh:20: the position channels of joint 'leg' change"), InputError);
  }
  SUBCASE("read_bvh names a missing file") {
    CHECK_THROWS_WITH_AS(read_bvh("/nonexistent/x.bvh"), doctest::Contains("/nonexistent/x.bvh"), InputError);
  }
}

TEST_CASE("lengths past 1e6 m and frame times past 1e-5..1e4 s give an error naming the file and the line") {
  // Finite in the file's doubles, but infinite in our floats (found by the BVH fuzz target, whose seeds the
  // build writes these inputs among): an OFFSET of 1e39 cm would have been read as infinity and written
  // back as "inf".
  CHECK_THROWS_WITH_AS(read_bvh(test::fuzz_seeds() + "/bvh/offset_overflow.bvh"),
                       doctest::Contains("offset_overflow.bvh:8: the OFFSET is 1e+37 m after unit scaling: more than the 1e6 m a length may be"),
                       InputError);
  CHECK_THROWS_WITH_AS(read_bvh(test::fuzz_seeds() + "/bvh/frame_time_tiny.bvh"),
                       doctest::Contains("frame_time_tiny.bvh:18: frame time '1e-300' is outside 1e-05 to 10000 seconds"),
                       InputError);
  CHECK_THROWS_WITH_AS(parse_bvh(replace_line(kSmall, 20, "1.5 1e300 0 0 0 0 45 0 0"), "far.bvh"),
                       doctest::Contains("far.bvh:20: the root position of frame 1 is"), InputError);
  CHECK_THROWS_WITH_AS(parse_bvh(replace_line(kSmall, 18, "Frame Time: 1e5"), "slow.bvh"),
                       doctest::Contains("slow.bvh:18: frame time '1e5' is outside"), InputError);
  // The limits leave real files alone: a kilometre in centimetres, 1000 fps.
  CHECK(parse_bvh(replace_line(replace_line(kSmall, 20, "1.5 100000 0 0 0 0 45 0 0"), 18, "Frame Time: 0.001"), "ok.bvh")
            .frames[1].root_position.y == doctest::Approx(1000.0f));
}

TEST_CASE("constant position channels on a non-root joint fold into its offset") {
  std::string text = replace_line(kSmall, 9, "    CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation");
  SUBCASE("values that restate the OFFSET (MotionBuilder style)") {
    text = replace_line(text, 19, "0 100 0 0 0 0 0 -10 0 90 0 0");
    text = replace_line(text, 20, "1.5 100 0 0 0 0 0 -10 0 45 0 0");
    const Clip clip = parse_bvh(text, "mb.bvh");
    CHECK(clip.skeleton->joints[1].offset.y == doctest::Approx(-0.1));
  }
  SUBCASE("other values are added to the OFFSET") {
    text = replace_line(text, 19, "0 100 0 0 0 0 2 0 0 90 0 0");
    text = replace_line(text, 20, "1.5 100 0 0 0 0 2 0 0 45 0 0");
    const Clip clip = parse_bvh(text, "add.bvh");
    CHECK(clip.skeleton->joints[1].offset.x == doctest::Approx(0.02));
    CHECK(clip.skeleton->joints[1].offset.y == doctest::Approx(-0.1));
  }
}

TEST_CASE("numbers parse the same under a comma-decimal locale") {
  // setup.sh installs locales-all, so a German locale exists; its decimal separator is ','.
  const char* const candidates[] = {"de_DE.UTF-8", "de_DE.utf8", "de_DE", "fr_FR.UTF-8", "fr_FR.utf8"};
  const std::string previous = std::setlocale(LC_NUMERIC, nullptr);
  const char* chosen = nullptr;
  for (const char* name : candidates)
    if (std::setlocale(LC_NUMERIC, name) && std::string(std::localeconv()->decimal_point) == ",") {
      chosen = name;
      break;
    }
  REQUIRE_MESSAGE(chosen != nullptr, "no comma-decimal locale is installed (scripts/setup.sh installs locales-all)");
  CHECK(std::string(std::localeconv()->decimal_point) == ",");
  // A locale-dependent parser (strtod, iostreams with the global locale) would stop at the '.' here.
  const Clip clip = parse_bvh(kSmall, "locale.bvh");
  CHECK(clip.frames[1].root_position.x == doctest::Approx(0.015));
  CHECK(clip.fps == doctest::Approx(2.0));
  // ... and a comma in the file is an error naming the line, not a silent misreading.
  const std::string comma = replace_line(kSmall, 20, "1,5 100 0 0 0 0 45 0 0");
  CHECK_THROWS_WITH_AS(parse_bvh(comma, "comma.bvh"), doctest::Contains("comma.bvh:20: '1,5' is not a number"), InputError);
  // The writer does not use the locale either.
  CHECK(format_bvh(clip).find("Frame Time: 0.5\n") != std::string::npos);
  std::setlocale(LC_NUMERIC, previous.c_str());
}

TEST_CASE("every truncation and single-byte corruption of a valid file loads or throws InputError naming it") {
  const std::string text(kSmall);
  const char replacements[] = {'{', '}', 'x', '\n', '-', '9', ' ', '.', 'e', '\0'};
  auto try_parse = [](const std::string& t) {
    try {
      const Clip clip = parse_bvh(t, "mutant.bvh");
      CHECK(clip.frame_count() >= 1);
      CHECK(clip.skeleton->size() >= 1);
      for (const Pose& p : clip.frames) CHECK(p.rotations.size() == static_cast<size_t>(clip.skeleton->size()));
    } catch (const InputError& e) {
      CHECK(e.file() == "mutant.bvh");
      CHECK(e.line() >= 1);
    }
  };
  for (size_t cut = 0; cut <= text.size(); ++cut) try_parse(text.substr(0, cut));
  for (size_t i = 0; i < text.size(); ++i)
    for (char r : replacements) {
      std::string t = text;
      t[i] = r;
      try_parse(t);
    }
}

TEST_CASE("a repeated joint name is an error naming its line") {
  CHECK_THROWS_WITH_AS(parse_bvh(replace_line(kSmall, 6, "  JOINT hips"), "twice.bvh"),
                       doctest::Contains("twice.bvh:6: joint name 'hips' repeats"), InputError);
}

TEST_CASE("a very deep hierarchy reads and writes without recursion") {
  const int depth = 20000;
  std::string text = "HIERARCHY\nROOT j0\n{\nOFFSET 0 0 0\nCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n";
  for (int i = 1; i < depth; ++i) text += "JOINT j" + std::to_string(i) + "\n{\nOFFSET 0 1 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n";
  text += "End Site\n{\nOFFSET 0 1 0\n}\n";
  for (int i = 0; i < depth; ++i) text += "}\n";
  text += "MOTION\nFrames: 1\nFrame Time: 0.1\n0 0 0";
  for (int i = 0; i < depth; ++i) text += " 0 0 0";
  text += "\n";
  const Clip clip = parse_bvh(text, "deep.bvh");
  REQUIRE(clip.skeleton->size() == depth);
  const WorldPose w = world(clip, 0);
  CHECK(w.positions.back().y == doctest::Approx(0.01 * (depth - 1)).epsilon(1e-3));  // float sums of 20000 bones
  const Clip again = parse_bvh(format_bvh(clip), "deep.bvh");
  CHECK(again.skeleton->size() == depth);
  CHECK(world(again, 0).positions.back().y == doctest::Approx(0.01 * (depth - 1)).epsilon(1e-3));  // float sums of 20000 bones
}
