#include "engine/control/policy.h"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "engine/util/error.h"
#include "engine/util/files.h"

namespace prep {
namespace {

constexpr char kMagic[8] = {'P', 'R', 'E', 'P', 'P', 'O', 'L', '\x1a'};

class Writer {
 public:
  void bytes(const void* p, size_t n) { out.append(static_cast<const char*>(p), n); }
  void u8(std::uint8_t v) { bytes(&v, 1); }
  void u32(std::uint32_t v) {
    unsigned char b[4];
    for (int i = 0; i < 4; ++i) b[i] = static_cast<unsigned char>(v >> (8 * i));
    bytes(b, 4);
  }
  void u64(std::uint64_t v) {
    unsigned char b[8];
    for (int i = 0; i < 8; ++i) b[i] = static_cast<unsigned char>(v >> (8 * i));
    bytes(b, 8);
  }
  void i32(int v) { u32(static_cast<std::uint32_t>(v)); }
  void f32(float v) {
    std::uint32_t u;
    std::memcpy(&u, &v, 4);
    u32(u);
  }
  void str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    bytes(s.data(), s.size());
  }
  std::string out;
};

class Reader {
 public:
  Reader(std::string_view data, const std::string& source) : data_(data), source_(source) {}
  void need(size_t n, const char* what) {
    if (data_.size() - pos_ < n)
      throw InputError(source_, "truncated: " + std::string(what) + " at byte " + std::to_string(pos_) +
                                    " runs past the end (" + std::to_string(data_.size()) + " bytes)");
  }
  std::uint8_t u8(const char* what) {
    need(1, what);
    return static_cast<std::uint8_t>(data_[pos_++]);
  }
  std::uint32_t u32(const char* what) {
    need(4, what);
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(static_cast<unsigned char>(data_[pos_ + i])) << (8 * i);
    pos_ += 4;
    return v;
  }
  std::uint64_t u64(const char* what) {
    need(8, what);
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(static_cast<unsigned char>(data_[pos_ + i])) << (8 * i);
    pos_ += 8;
    return v;
  }
  int i32(const char* what) { return static_cast<int>(u32(what)); }
  float f32(const char* what) {
    const std::uint32_t u = u32(what);
    float v;
    std::memcpy(&v, &u, 4);
    return v;
  }
  std::string str(const char* what) {
    const std::uint32_t n = u32(what);
    need(n, what);
    std::string s(data_.substr(pos_, n));
    pos_ += n;
    return s;
  }
  size_t pos() const { return pos_; }

 private:
  std::string_view data_;
  const std::string& source_;
  size_t pos_ = 0;
};

}  // namespace

std::uint64_t fnv1a64(std::string_view bytes) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

Policy make_policy(const Params& params, const ActionTable& table, const ActionSpace& actions, const TrainingResult& r,
                   const std::string& target) {
  Policy p;
  p.params_hash = policy_params_hash(params);
  p.quantization = params.quantization;
  p.target = target;
  p.table = table;
  for (int m = 0; m < actions.motions(); ++m) p.allowed_masks.push_back(actions.allowed_mask(m));
  p.steps = r.steps;
  p.episodes = r.episodes;
  p.converged = r.converged;
  p.seed = params.sarsa.seed;
  p.threads = params.sarsa.threads;
  p.states = static_cast<int>(r.q.size() / static_cast<size_t>(actions.size()));
  p.actions = actions.size();
  p.q = r.q;
  return p;
}

ActionSpace Policy::action_space() const { return ActionSpace::from_masks(table.motions, table.alpha_levels, allowed_masks); }

std::string serialize_policy(const Policy& p) {
  Writer w;
  w.bytes(kMagic, 8);
  w.u32(kPolicyFormatVersion);
  w.u64(0);  // total size, patched below
  w.u64(p.params_hash);
  const QuantizationParams& q = p.quantization;
  w.f32(q.d_step);
  w.i32(q.d_g_bins);
  w.i32(q.d_i_bins);
  w.f32(q.theta_g_step_deg);
  w.i32(q.theta_g_bins);
  w.f32(q.theta_i_step_deg);
  w.i32(q.theta_i_bins);
  w.f32(q.alpha_step);
  w.i32(q.alpha_levels);
  w.str(p.target);
  w.f32(p.table.curve.C);
  w.f32(p.table.curve.c);
  w.u8(p.table.curve.linear ? 1 : 0);
  w.u32(static_cast<std::uint32_t>(p.table.motions));
  for (int m = 0; m < p.table.motions; ++m) {
    w.str(p.table.motion_names[static_cast<size_t>(m)]);
    w.str(p.table.motion_roles[static_cast<size_t>(m)]);
    w.u64(p.allowed_masks[static_cast<size_t>(m)]);
  }
  for (const ActionEffect& e : p.table.effects) {
    w.f32(e.forward);
    w.f32(e.left);
    w.f32(e.turn);
    w.f32(e.duration);
  }
  w.u64(static_cast<std::uint64_t>(p.steps));
  w.u64(static_cast<std::uint64_t>(p.episodes));
  w.u8(p.converged ? 1 : 0);
  w.u64(p.seed);
  w.u32(static_cast<std::uint32_t>(p.threads));
  w.u32(static_cast<std::uint32_t>(p.states));
  w.u32(static_cast<std::uint32_t>(p.actions));
  for (float v : p.q) w.f32(v);
  const std::uint64_t total = w.out.size() + 8;
  for (int i = 0; i < 8; ++i) w.out[12 + static_cast<size_t>(i)] = static_cast<char>(total >> (8 * i));
  w.u64(fnv1a64(w.out));
  return std::move(w.out);
}

void save_policy(const Policy& policy, const std::string& path) { write_file_atomic(path, serialize_policy(policy)); }

Policy parse_policy(std::string_view bytes, const std::string& source, const Params& expected) {
  if (bytes.size() < 8 || std::memcmp(bytes.data(), kMagic, 8) != 0)
    throw InputError(source, "not a prep policy file (bad magic)");
  Reader r(bytes, source);
  for (int i = 0; i < 8; ++i) r.u8("magic");
  const std::uint32_t version = r.u32("format version");
  if (version != kPolicyFormatVersion)
    throw InputError(source, "policy format version " + std::to_string(version) + " is not supported (this build reads " +
                                 std::to_string(kPolicyFormatVersion) + ")");
  const std::uint64_t total = r.u64("file size");
  if (bytes.size() < total)
    throw InputError(source, "truncated: " + std::to_string(bytes.size()) + " of " + std::to_string(total) + " bytes");
  if (bytes.size() > total || total < 8)
    throw InputError(source, "corrupt: " + std::to_string(bytes.size()) + " bytes where the header says " +
                                 std::to_string(total));
  const std::string_view body = bytes.substr(0, total - 8);
  Reader tail(bytes.substr(total - 8), source);
  if (tail.u64("checksum") != fnv1a64(body))
    throw InputError(source, "corrupt: checksum mismatch (the file was damaged after it was written)");

  Policy p;
  p.params_hash = r.u64("params hash");
  QuantizationParams& q = p.quantization;
  q.d_step = r.f32("quantization");
  q.d_g_bins = r.i32("quantization");
  q.d_i_bins = r.i32("quantization");
  q.theta_g_step_deg = r.f32("quantization");
  q.theta_g_bins = r.i32("quantization");
  q.theta_i_step_deg = r.f32("quantization");
  q.theta_i_bins = r.i32("quantization");
  q.alpha_step = r.f32("quantization");
  q.alpha_levels = r.i32("quantization");
  p.target = r.str("target");
  p.table.curve.C = r.f32("root curve");
  p.table.curve.c = r.f32("root curve");
  p.table.curve.linear = r.u8("root curve") != 0;
  const std::uint32_t motions = r.u32("motion count");
  if (motions == 0 || motions > 64) throw InputError(source, "corrupt: " + std::to_string(motions) + " core motions");
  p.table.motions = static_cast<int>(motions);
  p.table.alpha_levels = q.alpha_levels;
  q.core_roles.clear();
  for (std::uint32_t m = 0; m < motions; ++m) {
    p.table.motion_names.push_back(r.str("motion name"));
    p.table.motion_roles.push_back(r.str("motion role"));
    q.core_roles.push_back(p.table.motion_roles.back());
    p.allowed_masks.push_back(r.u64("allowed actions"));
  }

  // Refuse another configuration before trusting any count in the file.
  const std::uint64_t want = policy_params_hash(expected);
  if (p.params_hash != want)
    throw InputError(source, "trained for another configuration (params hash " + std::to_string(p.params_hash) +
                                 ", this run's is " + std::to_string(want) +
                                 "): quantization, rewards, SARSA constants or the lower-body blend curve differ");

  StateSpace space = [&] {
    try {
      return StateSpace(q, p.table.motions);
    } catch (const std::invalid_argument& e) {
      throw InputError(source, std::string("corrupt quantization: ") + e.what());
    }
  }();
  const int actions = p.table.motions * q.alpha_levels;
  if (actions > 64) throw InputError(source, "corrupt: too many actions");
  for (int a = 0; a < actions; ++a) {
    ActionEffect e;
    e.forward = r.f32("action table");
    e.left = r.f32("action table");
    e.turn = r.f32("action table");
    e.duration = r.f32("action table");
    e.precompute();
    p.table.effects.push_back(e);
  }
  p.steps = static_cast<std::int64_t>(r.u64("training record"));
  p.episodes = static_cast<std::int64_t>(r.u64("training record"));
  p.converged = r.u8("training record") != 0;
  p.seed = r.u64("training record");
  p.threads = static_cast<int>(r.u32("training record"));
  p.states = static_cast<int>(r.u32("state count"));
  p.actions = static_cast<int>(r.u32("action count"));
  if (p.states != space.size() || p.actions != actions)
    throw InputError(source, "corrupt: " + std::to_string(p.states) + " x " + std::to_string(p.actions) +
                                 " Q values where the quantization gives " + std::to_string(space.size()) + " x " +
                                 std::to_string(actions));
  const size_t n = static_cast<size_t>(p.states) * static_cast<size_t>(p.actions);
  if (body.size() - r.pos() != n * 4)
    throw InputError(source, "corrupt: the Q table holds " + std::to_string(body.size() - r.pos()) + " bytes, expected " +
                                 std::to_string(n * 4));
  p.q.resize(n);
  for (size_t i = 0; i < n; ++i) p.q[i] = r.f32("Q table");
  try {
    (void)p.action_space();
  } catch (const std::invalid_argument& e) {
    throw InputError(source, std::string("corrupt allowed actions: ") + e.what());
  }
  return p;
}

Policy load_policy(const std::string& path, const Params& expected) {
  return parse_policy(read_file(path), path, expected);
}

}  // namespace prep
