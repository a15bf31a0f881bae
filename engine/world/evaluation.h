// Measured quality: how natural a world's motion is, in numbers anyone can regenerate.
//
// An EvaluationRecorder watches a World tick by tick (observe() after every World::step) and measures,
// per character and in total:
//   reached_goal, time_to_goal_s                       (the user; opponents have no goal)
//   per launched target motion: action, alpha_at_launch, prep_lead_s, peak_decel_mps2, speed_at_launch_mps
//   foot_skate_cm_per_frame, com_in_support, pose_plausibility (cm), synthesis_us_per_frame.
// The three methods compared (EvaluationMethod): "ours" (the paper: per-joint curves, Eq. 1), "linear" (one
// blend weight alpha for every joint, BlendParams::method, with its own policy since the root curve shapes the
// stride, Sec. 8) and "naive" (motion-graph concatenation without preparation: World::set_preparation(false),
// alpha = 0 until the launch).
//
// Definitions, and the choices made where the definitions leave room (each is coded below in evaluation.cpp):
// - Synthesized frames. The pose of a character playing a target clip is the recorded clip itself, the
//   same for every method (and a crawl's hands and knees, a jump's flight, are outside what a foot skate or
//   a support polygon of the feet can judge). Skate, balance and plausibility are therefore measured on the
//   frames the method makes: every frame not inside a target motion, plus the cross-fade into it (the first
//   GraphParams::blend_s after a launch).
// - Foot skate (the motion in-betweening / MANN measure, restricted to feet in contact):
//   for each foot the contact labels have down (WorldCharacter::contacts: the locomotion's labels, which
//   synthesis keeps, Sec. 5.2), the horizontal slide since the previous frame of its point in contact (heel
//   or toe tip; both: the one nearer its planted height), weighted by clamp(2 - 2^(h/H), 0, 1) with h its
//   height above its planted height and H = 2.5 cm, scaled to a 60 Hz frame; the mean over those
//   (frame, foot) pairs. Without the contact labels the weight alone would count a swinging toe that skims
//   the floor (real toe clearance is 1-2 cm: the CMU walks would score 1-2 cm/frame). Planted heights come
//   from the motion database (EvaluationReference): the median height of each point over the frames where
//   the set's contact detection has it down, so an ankle joint that rests 7 cm above the sole is down at 7.
// - Deceleration: horizontal root speed over 0.1 s (6 ticks at 60 Hz; one tick's difference would turn a
//   1 mm wobble into 3.6 m/s^2), deceleration = the fall of that speed over the next 0.1 s, per second. A
//   turn at constant speed is no deceleration. The window is the second before the launch AND the launch's
//   cross-fade (blend_s): "stopping absurdly" happens where a character at full speed is handed to a target
//   clip that starts slow, at the launch itself, and a window that ended at the launch would miss it.
// - prep_lead_s: from the start of the run of alpha > 0.1 that lasts until the launch, to the launch; a run
//   begun before the character's previous target motion counts from its return to locomotion (it kept its
//   preparation between two close obstacles). 0 when alpha at the launch is at most 0.1.
// - com_in_support: over synthesized frames with alpha >= 0.3 (where the balance optimizer works,
//   Sec. 5.3), the fraction whose COM projects inside the support polygon (WorldCharacter::com_in_support).
//   Undefined (NaN, null in JSON) when there are no such frames: naive never reaches 0.3.
// - pose_plausibility: mean over synthesized frames of the distance from the upper-body pose to its nearest
//   pose among all frames of all clips of the motion set (UpperBodyPoseIndex), in cm, RMS over the joints.
// - synthesis_us_per_frame: the World's synthesis stage time (World::stage_times, Synthesizer::step and the
//   cross-fades) per character-frame synthesized. The world times the stage summed over its characters,
//   so it is reported in total only.
// - A run (evaluate_scenario) lasts until the user has reached its goal and no character plays a target
//   motion, plus one second to come to rest, at most `max_seconds`.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "engine/motion/motion_set.h"
#include "engine/world/clearance.h"
#include "engine/world/world.h"

namespace prep {

// The constants that define the metrics. They are not tunables of the method: change one and the
// numbers mean something else, so they are fixed here rather than in Params.
namespace metric {
constexpr float kSkateHeight = 0.025f;        // m: H of the skate weight clamp(2 - 2^(h/H), 0, 1)
constexpr float kSkateFrameRate = 60.0f;      // Hz: slides are reported per frame at this rate
constexpr float kLeadAlpha = 0.1f;            // prep_lead_s counts from alpha first exceeding this
constexpr float kDecelWindow = 1.0f;          // s before the launch
constexpr float kSpeedSpan = 0.1f;            // s: speed and its change are taken over this span
constexpr float kBalanceAlpha = 0.3f;         // com_in_support counts frames with alpha >= this
constexpr float kSettle = 1.0f;               // s a run goes on after its end condition
}  // namespace metric

enum class EvaluationMethod { Ours, Linear, Naive };
const char* method_name(EvaluationMethod method);  // "ours", "linear", "naive"
std::optional<EvaluationMethod> parse_method(std::string_view name);
// The Params a method runs with: linear sets blend.method = "linear"; ours and naive keep `base`.
Params method_params(EvaluationMethod method, Params base);

// --- The measures on their own (hand-checkable) ---------------------------------------------------------

// clamp(2 - 2^(h/H), 0, 1): 1 on the floor, 0 from H up.
float skate_weight(float height_above_planted);
// The height-weighted horizontal slide (m) of one foot point from `previous` to `current`, whose planted
// height is `planted`, scaled to a kSkateFrameRate frame when the step is `dt` seconds.
float weighted_slide(const glm::vec3& previous, const glm::vec3& current, float planted, float dt);
// Largest deceleration (m/s^2) of a floor trajectory sampled every `dt` over samples [first, last] (each
// sample's deceleration is the fall of the kSpeedSpan speed ending there, see above); 0 if none is defined.
float peak_deceleration(const std::vector<glm::vec2>& positions, float dt, int first, int last);
// Horizontal speed (m/s) over the kSpeedSpan ending at sample k (0 before there is a span).
float speed_at(const std::vector<glm::vec2>& positions, float dt, int k);
// Seconds from the start of the run of alpha > kLeadAlpha that ends at sample `launch` (not before sample
// `earliest`) to the launch; 0 when alpha[launch] <= kLeadAlpha.
float preparation_lead(const std::vector<float>& alpha, int launch, int earliest, float dt);

// --- The motion database the measures refer to ------------------------------------------------------------

// Nearest upper-body poses of a motion set. The feature of a pose: the positions of the upper-body chain
// joints (spine, neck, head, collars, shoulders, elbows, wrists: BodyMap; fingers left out, they would
// only weigh the hands more) relative to the root joint, in the root's heading frame (yaw removed, the
// pelvis' pitch and roll kept: leaning is part of the pose; the hips' height is not, crouching belongs to
// the lower body). Distance: RMS over those joints (m). The search is exact: a k-d tree over all frames of
// all clips (median splits on the widest dimension, buckets of 16, nearer side first, a side skipped when
// the splitting plane is farther than the best so far). Motion lies on a low-dimensional manifold of this
// 30-40-dimensional space, which is what makes the tree prune.
class UpperBodyPoseIndex {
 public:
  explicit UpperBodyPoseIndex(const MotionSet& set);
  int joints() const { return static_cast<int>(joints_.size()); }
  int dimension() const { return 3 * joints(); }
  size_t size() const { return count_; }

  // The feature of a pose (dimension() floats). `positions` is FK scratch.
  void feature(const Pose& pose, std::vector<glm::vec3>& positions, float* out) const;
  // RMS joint distance (m) from a feature to the nearest database feature; the brute-force scan is for tests.
  float nearest_distance(const float* feature) const;
  float nearest_distance_brute_force(const float* feature) const;
  float distance_to_database(const Pose& pose) const;  // allocates; for tests and tools

 private:
  struct Node {
    int begin = 0, end = 0;  // the features [begin, end) of features_ (tree order)
    int dim = -1;            // split dimension; -1 for a leaf
    float split = 0;
    int left = -1, right = -1;
  };
  int build(int begin, int end, std::vector<int>& order, const std::vector<float>& raw);
  void search(int node, const float* q, float& best) const;
  float squared_distance(const float* q, size_t item, float bound) const;

  std::shared_ptr<const Skeleton> skeleton_;
  std::vector<int> joints_;
  size_t count_ = 0;
  std::vector<float> features_;  // count_ x dimension(), in tree order
  std::vector<Node> nodes_;
};

// What the measures need of a motion set, made once per set and shared by the runs on it.
struct EvaluationReference {
  explicit EvaluationReference(const MotionSet& set);
  UpperBodyPoseIndex poses;
  std::array<std::array<float, 2>, 2> planted_height{};  // [side][0 = heel (ankle joint), 1 = toe tip], m
};

// The foot skate (as above, cm per 60 Hz frame) of a recorded clip played at 60 Hz with its own contact
// labels (the nearest frame's): the floor the synthesized motion is compared with.
double clip_foot_skate_cm_per_frame(const MotionSet& set, const MotionClip& clip, const EvaluationReference& reference);

// --- Results ----------------------------------------------------------------------------------------------

struct LaunchEvaluation {
  TargetAction action = TargetAction::Kick;
  float time = 0;                // s
  bool automatic = false;
  int object = -1, target_character = -1;
  float alpha_at_launch = 0;
  float prep_lead_s = 0;
  float peak_decel_mps2 = 0;
  float speed_at_launch_mps = 0;  // over the kSpeedSpan before the launch
  float min_clearance = 0;        // m: the nearest approach while its target motion played (clearance.h)
  float strike_gap = 0;           // m: a kick's foot to the ball's surface at the strike (NaN: not struck)
};

// Sums over frames; the metrics are their means.
struct FrameTotals {
  long frames = 0;                // ticks observed
  long synthesized_frames = 0;    // frames the method made (see above)
  long contact_foot_frames = 0;   // (synthesized frame, foot in contact) pairs
  double skate_m = 0;             // sum of their weighted slides per 60 Hz frame
  double plausibility_m = 0;      // sum of nearest upper-body distances
  long balance_frames = 0;        // synthesized frames with alpha >= kBalanceAlpha
  long balance_inside = 0;        // ... whose COM is inside the support polygon

  double foot_skate_cm_per_frame() const;
  double com_in_support() const;     // NaN when balance_frames == 0
  double pose_plausibility_cm() const;
  FrameTotals& operator+=(const FrameTotals& o);
};

struct CharacterEvaluation {
  int index = 0;
  Control control = Control::User;
  bool reached_goal = false;
  float time_to_goal_s = -1;      // -1: not reached (or no goal: opponents)
  std::vector<LaunchEvaluation> launches;
  FrameTotals totals;
  std::vector<float> alpha;       // per observed frame (times in Evaluation::times)
};

struct Evaluation {
  std::string scenario, motions;  // motions: the motion set's name
  EvaluationMethod method = EvaluationMethod::Ours;
  float seconds = 0;
  int ticks = 0;
  std::vector<float> times;       // of the observed frames
  std::vector<CharacterEvaluation> characters;
  int user = 0;
  double synthesis_us_per_frame = 0;
  long synthesis_calls = 0;       // character-frames synthesized by Synthesizer::step
  ClearanceSummary clearance;     // every character's bodies against the objects and each other

  FrameTotals totals() const;                 // over every character
  std::vector<LaunchEvaluation> launches() const;  // every character's, in time order
};

class EvaluationRecorder {
 public:
  // Observes the world's current state as the first frame. The reference must be of the world's set and
  // outlive the recorder.
  EvaluationRecorder(const World& world, const EvaluationReference& reference);
  void observe(const World& world);  // after every World::step()
  Evaluation finish(const World& world, EvaluationMethod method) const;

 private:
  struct Track {
    std::vector<glm::vec2> positions;
    std::vector<float> alpha;
    std::vector<int> launch_ticks;        // observed frame of each of this character's launches
    std::vector<int> launch_records;      // their index in World::launches()
    std::vector<int> return_ticks;        // observed frames at which a target motion ended
    bool in_target = false;
    int fade_until = -1;                  // frames up to this one are a launch's cross-fade
    std::array<std::array<glm::vec3, 2>, 2> feet{};  // [side][heel, toe] of the last frame
    bool has_feet = false;
    FrameTotals totals;
  };
  void measure_frame(const World& world, int index, Track& t, int tick);

  const EvaluationReference* reference_;
  ClearanceLog clearance_;
  std::vector<Track> tracks_;
  std::vector<float> times_;
  size_t launches_seen_ = 0;
  size_t first_launch_record_ = 0;  // World::launches() before the first frame (the clearance log skips them)
  double synthesis_ms_ = 0;
  long synthesis_calls_ = 0;
  std::vector<glm::vec3> positions_;
  std::vector<glm::quat> rotations_;
  std::vector<float> feature_;
};

// Runs a scenario headless with its auto launches under a method until the end condition above (at most
// max_seconds) and returns the measures. `assets` must be made with method_params(method, ...) (linear
// needs its own policy); naive turns preparation off in the world.
Evaluation evaluate_scenario(const Scenario& scenario, std::shared_ptr<const WorldAssets> assets,
                             const EvaluationReference& reference, EvaluationMethod method, float max_seconds);

// JSON (undefined metrics are null): {"scenario", "motions", "method", "seconds", "ticks",
//   "total": {"reached_goal", "time_to_goal_s", "launches": [{"action", "character", "time_s", "automatic",
//             "alpha_at_launch", "prep_lead_s", "peak_decel_mps2", "speed_at_launch_mps", "object"?,
//             "target_character"?}], "frames", "synthesized_frames", "foot_skate_cm_per_frame",
//             "com_in_support", "com_frames", "pose_plausibility", "synthesis_us_per_frame", "synthesis_calls"},
//   "characters": [{"index", "control", "reached_goal"? and "time_to_goal_s"? (the user), "launches", and the
//                   frame metrics as in "total"}]}
nlohmann::json evaluation_json(const Evaluation& e);

}  // namespace prep
