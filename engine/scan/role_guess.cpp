#include "engine/scan/role_guess.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <set>
#include <vector>

#include <glm/gtc/constants.hpp>

#include "engine/scan/target_timing.h"

namespace prep {
namespace {


std::set<std::string> words_of(const std::string& name) {
  std::set<std::string> words;
  std::string word;
  for (char c : name + " ") {
    if (std::isalpha(static_cast<unsigned char>(c))) {
      word += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else if (!word.empty()) {
      words.insert(word);
      word.clear();
    }
  }
  return words;
}

bool is_punch(Role r) { return r == Role::PunchLeft || r == Role::PunchRight; }

std::string format(const char* pattern, double a, double b = 0.0) {
  char text[160];
  std::snprintf(text, sizeof text, pattern, a, b);
  return text;
}

}  // namespace

std::optional<Role> role_from_name(const std::string& file_name) {
  const std::set<std::string> w = words_of(file_name);
  auto has = [&](std::initializer_list<const char*> any) {
    return std::any_of(any.begin(), any.end(), [&](const char* x) { return w.count(x) > 0; });
  };
  const bool left = has({"left", "l"}), right = has({"right", "r"});
  if (has({"crawl", "crawling"})) return Role::Crawl;
  if (has({"duck", "ducking"})) return Role::Duck;
  if (has({"jump", "jumping", "hop", "leap", "vault"})) return Role::Jump;
  if (has({"kick", "kicking"})) return Role::Kick;
  if (has({"punch", "punching", "jab", "cross", "hook", "box", "boxing"})) return left && !right ? Role::PunchLeft : Role::PunchRight;
  if (has({"turn", "turning"})) {
    if (left != right) return left ? Role::TurnLeft : Role::TurnRight;
  }
  if (has({"step", "sidestep"}) && left != right) return left ? Role::StepLeft : Role::StepRight;
  if (has({"idle", "stand", "standing"})) return Role::Idle;
  if (has({"walk", "walking", "run", "running", "jog", "jogging"})) return Role::Walk;
  return std::nullopt;
}

MotionRole role_from_motion(const MotionSignals& s, int first, int last) {
  const std::vector<float> head = smoothed(s.head_height, s.frames_in(0.05f));
  int low = first;
  for (int f = first; f <= last; ++f)
    if (head[static_cast<size_t>(f)] < head[static_cast<size_t>(low)]) low = f;
  const float head_drop = (s.standing_head - head[static_cast<size_t>(low)]) / s.standing_head;
  float wrist_low = 1e9f;
  for (int side : {kLeft, kRight})
    for (int f = first; f <= last; ++f) wrist_low = std::min(wrist_low, s.hand[static_cast<size_t>(side)][static_cast<size_t>(f)].y);
  const float speed = median_of(s.ground_speed, first, last);
  const std::vector<float> speed_around = smoothed(s.ground_speed, s.frames_in(0.25f));

  // Crawl: down near the floor on the hands, slowly.
  if (head_drop >= 0.4f && wrist_low < 0.3f && speed_around[static_cast<size_t>(low)] < 1.0f)
    return {Role::Crawl, 0.9f, format("head down %.0f%%, a wrist %.0f cm above the floor", 100.0 * head_drop, 100.0 * wrist_low)};

  // Jump: a long flight, high.
  std::vector<float> root_height(s.root.size());
  for (size_t f = 0; f < root_height.size(); ++f) root_height[f] = s.root[f].y;
  const float usual_root = median_of(root_height, first, last);
  float longest = 0.0f, highest = 0.0f;
  for (const Flight& fl : flights(s, first, last)) {
    longest = std::max(longest, s.seconds(fl.length()));
    for (int f = fl.first; f <= fl.last; ++f) highest = std::max(highest, root_height[static_cast<size_t>(f)] - usual_root);
  }
  if (longest >= 0.15f && highest >= 0.2f)
    return {Role::Jump, 0.9f, format("a %.2f s flight, the root %.0f cm up", longest, 100.0 * highest)};

  // Duck: the head down on the move, and back up.
  const float end_drop = (s.standing_head - head[static_cast<size_t>(last)]) / s.standing_head;
  if (head_drop >= 0.2f && speed_around[static_cast<size_t>(low)] >= 0.5f && end_drop < 0.5f * head_drop)
    return {Role::Duck, 0.7f, format("head down %.0f%% at %.1f m/s, and back up", 100.0 * head_drop, speed_around[static_cast<size_t>(low)])};

  // Kick: a foot far faster than the body.
  const Strike foot = fastest_foot(s, first, last);
  const float foot_excess = foot.speed - s.ground_speed[static_cast<size_t>(foot.peak)];
  // One strike, not a stride: the same foot is nowhere else (0.5 s or more away) three quarters as fast.
  float elsewhere = 0.0f;
  const std::vector<float>& kicking = s.foot_speed[static_cast<size_t>(foot.limb)];
  for (int f = first; f <= last; ++f)
    if (std::abs(f - foot.peak) >= s.frames_in(0.5f)) elsewhere = std::max(elsewhere, kicking[static_cast<size_t>(f)]);
  if (foot_excess >= 6.0f && elsewhere < 0.75f * foot.speed)
    return {Role::Kick, 0.7f, format("a foot at %.1f m/s, %.1f m/s faster than the body", foot.speed, foot_excess)};

  // Punch: a hand striking while the body keeps its place.
  std::vector<Strike> strikes = hand_strikes(s, first, last);
  strikes.erase(std::remove_if(strikes.begin(), strikes.end(),
                               [&](const Strike& k) { return speed_around[static_cast<size_t>(k.peak)] >= 1.5f; }),
                strikes.end());
  if (!strikes.empty()) {
    const Strike& k = *std::max_element(strikes.begin(), strikes.end(), [](const Strike& a, const Strike& b) { return a.speed < b.speed; });
    return {k.limb == kLeft ? Role::PunchLeft : Role::PunchRight, 0.7f, format("a hand striking at %.1f m/s (%.0f strikes)", k.speed, static_cast<double>(strikes.size()))};
  }

  if (speed < 0.25f) return {Role::Idle, 0.8f, format("standing (%.2f m/s)", speed)};

  // Turn: the heading, smoothed over a second, turns far and steadily.
  const std::vector<float> heading = smoothed(s.heading, s.frames_in(0.5f));
  const float turned = heading[static_cast<size_t>(last)] - heading[static_cast<size_t>(first)];
  const float rate = std::abs(turned) / std::max(1e-3f, s.seconds(last - first));
  if (std::abs(turned) >= 60.0f * glm::pi<float>() / 180.0f && rate >= 15.0f * glm::pi<float>() / 180.0f)
    return {turned > 0.0f ? Role::TurnLeft : Role::TurnRight, 0.7f, format("turns %.0f degrees at %.1f m/s", turned * 180.0 / glm::pi<float>(), speed)};

  return {Role::Walk, 0.8f, format("moves at %.2f m/s, turning %.0f degrees", speed, turned * 180.0 / glm::pi<float>())};
}

RoleGuess guess_role(const std::string& file_name, const MotionSignals& s, int first, int last) {
  const std::optional<Role> named = role_from_name(file_name);
  const MotionRole shown = role_from_motion(s, first, last);
  RoleGuess g;
  if (!named) {
    g.role = shown.role;
    g.confidence = shown.strength;
    g.evidence = std::string("the motion: ") + shown.reason;
    return g;
  }
  g.role = *named;
  const bool agree = shown.role == *named || (is_punch(shown.role) && is_punch(*named));
  g.confidence = agree ? 0.95f : 0.6f;
  g.evidence = std::string("named ") + role_name(*named) + (agree ? "; the motion agrees: " : "; the motion looks like " +
                                                                   std::string(role_name(shown.role)) + ": ") + shown.reason;
  return g;
}

}  // namespace prep
