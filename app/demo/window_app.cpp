#include "app/demo/window_app.h"

#include "app/render/gl_api.h"

namespace prep::demo {

void WindowApp::start_frame_timing(bool measured) {
  const auto now = Clock::now();
  if (measured && measured_frame_before_) timings.end_frame(std::chrono::duration<double, std::milli>(now - last_frame_start_).count());
  last_frame_start_ = now;
  measured_frame_before_ = measured;
}

void WindowApp::finish_stage(int stage, Clock::time_point start, bool gl_stage, bool measured) {
  if (gl_stage && sync_stages) gl::glFinish();
  if (measured) timings.add(stage, ms_since(start));
}

}  // namespace prep::demo
