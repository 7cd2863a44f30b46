#include "stickslip/run/shard.hpp"

#include <fmt/format.h>

#include <cstdio>

#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"

namespace stickslip::run {

std::string shard::tag() const { return fmt::format("shard-{}-of-{}", index, count); }

std::optional<shard> shard::of_run(const std::string& run_id) {
  unsigned long long i = 0, n = 0;
  int end = 0;
  if (std::sscanf(run_id.c_str(), "shard-%llu-of-%llu%n", &i, &n, &end) != 2 || n == 0 || i >= n)
    return std::nullopt;
  const shard s{i, n};
  if (run_id.compare(0, static_cast<std::size_t>(end), s.tag()) != 0) return std::nullopt;
  return s;
}

std::optional<shard> parse_shard(const std::string& text) {
  if (text.empty()) return std::nullopt;
  const auto slash = text.find('/');
  if (slash == std::string::npos)
    throw invalid_value("--shard", text, "i/n with 0 <= i < n, e.g. 3/16");
  shard sh;
  sh.count = io::parse_unsigned("--shard (n)", text.substr(slash + 1), 1, 1u << 20);
  sh.index = io::parse_unsigned("--shard (i)", text.substr(0, slash), 0, sh.count - 1);
  return sh;
}

}  // namespace stickslip::run
