// The windowed demo: a GLFW window, mouse and keyboard camera, the panels.
#pragma once

#include <string>
#include <vector>

#include "app/demo/motions.h"

namespace prep::demo {

// One scripted key press: at frame `frame`, press `key` (GLFW key code), as if typed.
struct ScriptedKey {
  int frame = 0;
  int key = 0;
};

// Parses "FRAME:KEY,FRAME:KEY,..." with KEY a letter, a digit, or one of space, left, right, up, down,
// escape (e.g. "20:e,40:space"). Throws std::invalid_argument naming the bad item.
std::vector<ScriptedKey> parse_key_script(const std::string& text);

struct WindowOptions {
  int width = 1280;
  int height = 720;
  int clip = 0;
  bool vsync = true;
  std::vector<ScriptedKey> script;
  std::string screenshot;       // written after frame `screenshot_after` (from the back buffer), then quit;
  int screenshot_after = 60;    // -1: when the demo is closed (Escape or the window's close button)
  int quit_after = -1;          // frames; -1 runs until the window closes
};

// Runs the window until closed. Throws render::NoDisplayError when no window can be opened.
void run_window(const DemoMotions& motions, const WindowOptions& options);

}  // namespace prep::demo
