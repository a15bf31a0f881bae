// Feeds each input to parse_policy as the bytes of a policy file, twice: as it is, then with its header's
// file size, its params hash and its trailing checksum rewritten to match, so that mutations get past the
// integrity checks into the counts, strings, tables and allowed-action masks behind them. Failure: anything
// but an InputError naming "fuzz.policy" (a crash, a sanitizer report, a leak, an escaping exception, an
// input slower than the run's -timeout).
#include <cstring>
#include <string>

#include "engine/control/policy.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

void put_u64(std::string& bytes, size_t at, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) bytes[at + static_cast<size_t>(i)] = static_cast<char>((v >> (8 * i)) & 0xff);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const prep::Params params;
  static const std::uint64_t hash = prep::policy_params_hash(params);
  const std::string source = "fuzz.policy";
  std::string bytes(prep::fuzz::bytes(data, size));
  prep::fuzz::expect_clean(source, [&] { (void)prep::parse_policy(bytes, source, params); });
  // Layout (policy.h): magic 8, version 4, file size 8 at 12, params hash 8 at 20, ..., checksum 8 at the end.
  if (bytes.size() >= 36) {
    put_u64(bytes, 12, bytes.size());
    put_u64(bytes, 20, hash);
    put_u64(bytes, bytes.size() - 8, prep::fnv1a64(std::string_view(bytes).substr(0, bytes.size() - 8)));
    prep::fuzz::expect_clean(source, [&] { (void)prep::parse_policy(bytes, source, params); });
  }
  return 0;
}
