#include "app/demo/timings.h"

namespace prep::demo {

const char* stage_name(int stage) {
  static const char* names[kStageCount] = {"update", "scene", "shadow map", "main pass", "panels", "finish"};
  return stage >= 0 && stage < kStageCount ? names[stage] : "?";
}

void Timings::add(int stage, double ms) {
  average_[stage] = seen_[stage] ? average_[stage] + smoothing_ * (ms - average_[stage]) : ms;
  seen_[stage] = true;
}

void Timings::end_frame(double frame_ms) {
  frame_ms_ = frame_seen_ ? frame_ms_ + smoothing_ * (frame_ms - frame_ms_) : frame_ms;
  frame_seen_ = true;
}

}  // namespace prep::demo
