// The windowed demo under a virtual display (scripts/xvfb_smoke.sh): it starts, a held key steers the
// World's goal (the script checks what the demo prints on closing), and the screenshot taken from the
// window shows the scene in the middle and the panels in their columns. Skipped without xvfb-run.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include "app/render/image.h"
#include "app/render/palette.h"
#include "app/ui/panels.h"
#include "tests/support/paths.h"

using namespace prep;
using render::palette::PixelClass;

namespace {

// <build>/tests/prep_tests_render -> <build>
std::string build_dir() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : self.parent_path().parent_path().string();
}

struct Counts {
  std::map<PixelClass, int> classes;
  int dark = 0, total = 0;
};

Counts count(const render::Image& image, int x0, int y0, int x1, int y1) {
  Counts c;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const std::uint8_t* p = image.pixel(x, y);
      c.classes[render::palette::classify(p[0], p[1], p[2])]++;
      c.dark += std::max({p[0], p[1], p[2]}) < 90;
      ++c.total;
    }
  return c;
}

// Whether the windowed demo can run here (xvfb-run and build/prep-demo exist); says why it is skipped if
// not. Makes the folder the tests write their logs and images to.
bool windowed_demo_runs(const std::string& build) {
  if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0 || build.empty() ||
      !std::filesystem::exists(build + "/prep-demo")) {
    MESSAGE("skipped: xvfb-run or " << build << "/prep-demo missing");
    return false;
  }
  std::filesystem::create_directories(test::tmp_dir());
  return true;
}

}  // namespace

TEST_CASE("windowed demo under Xvfb: a held key steers the goal, the window shows the scene and the panels") {
  const std::string build = build_dir();
  if (!windowed_demo_runs(build)) return;
  const std::string png = test::tmp_dir() + "/xvfb_demo.png", log = test::tmp_dir() + "/xvfb_demo.log";
  // Under AddressSanitizer the window's leaks are not checked: GLFW unloads Mesa's GLX driver when it
  // terminates, so LeakSanitizer sees the driver's allocations from an unknown module and cannot be told
  // to leave them by name. (Every other render test runs the same DemoApp through OSMesa, leak-checked.)
  const std::string command = "ASAN_OPTIONS=\"${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0\" " + test::repo() +
                              "/scripts/xvfb_smoke.sh '" + build + "' '" + png + "' > '" + log + "' 2>&1";
  const int status = std::system(command.c_str());
  INFO("log: " << log);
  REQUIRE(status == 0);  // the script checked that the keys steered the goal and that a 1280x720 PNG came out
  const render::Image image = render::read_png(png);
  REQUIRE(image.width == 1280);
  REQUIRE(image.height == 720);
  // The middle, between the panel columns: floor, sky and the character.
  const int left = static_cast<int>(ui::kMargin + ui::kLeftWidth) + 10;
  const int right = image.width - static_cast<int>(ui::kMargin + ui::kRightWidth) - 10;
  Counts middle = count(image, left, 0, right, image.height);
  CHECK(middle.classes[PixelClass::Ground] > middle.total / 4);
  CHECK(middle.classes[PixelClass::Sky] > 2000);
  CHECK(middle.classes[PixelClass::Character] > 300);
  // The columns: the top of each is a panel (dark, ImGui's window background), not the sky.
  Counts left_panel = count(image, static_cast<int>(ui::kMargin) + 4, 30, static_cast<int>(ui::kMargin + ui::kLeftWidth) - 4, 200);
  Counts right_panel = count(image, image.width - static_cast<int>(ui::kMargin + ui::kRightWidth) + 4, 30,
                                   image.width - static_cast<int>(ui::kMargin) - 4, 200);
  CHECK(left_panel.dark > left_panel.total / 2);
  CHECK(right_panel.dark > right_panel.total / 2);
  CHECK(left_panel.classes[PixelClass::Sky] < left_panel.total / 100);  // a few anti-aliased text pixels at most
  CHECK(right_panel.classes[PixelClass::Sky] < right_panel.total / 100);
}

// Label "slow": the sanitizer tree leaves it out (scripts/test.sh); the first test above runs the window there.
TEST_CASE("windowed demo under Xvfb: 60 s of live edits under stress with a broken Params file named and the old values kept" *
          doctest::test_suite("slow")) {
  const std::string build = build_dir();
  if (!windowed_demo_runs(build)) return;
  const std::string log = test::tmp_dir() + "/xvfb_stress.log";
  // Leaks unchecked for the same reason as above (the window's GLX driver).
  const std::string command = "ASAN_OPTIONS=\"${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0\" timeout 300 xvfb-run -a -s '-screen 0 1280x720x24' '" +
                              build + "/prep-demo' --no-vsync --stress 60 --stress-seed 7 > '" + log + "' 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream in(log);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  INFO("log: " << log << "\n" << text.substr(text.size() > 2000 ? text.size() - 2000 : 0));
  CHECK(status == 0);  // no crash, and the stress run's own checks passed
  CHECK(text.find("stress: ") != std::string::npos);
  CHECK(text.find("(names the file), old values kept: ok") != std::string::npos);
  CHECK(text.find("'balance.w_b' has the wrong type") != std::string::npos);
}
