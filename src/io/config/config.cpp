// Grid specifications, numbers and switch-time lists: text -> validated values.
// The TOML side is in config_toml.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"
#include "config_detail.hpp"

namespace stickslip::io {
namespace {

constexpr std::size_t max_grid_values = 1'000'000;
constexpr const char* grid_forms = "a list 'a,b,c', 'lin:a:b:n' or 'log:a:b:n'";

std::string_view trim(std::string_view s) noexcept {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view s, char sep) {
  std::vector<std::string_view> parts;
  std::size_t from = 0;
  while (true) {
    const auto at = s.find(sep, from);
    parts.push_back(s.substr(from, at == std::string_view::npos ? s.npos : at - from));
    if (at == std::string_view::npos) return parts;
    from = at + 1;
  }
}

// Parses the whole of `t` as a double; describes the problem in `why` on failure.
bool to_double(std::string_view t, double& out, std::string& why) {
  t = trim(t);
  if (t.empty()) {
    why = "an empty entry";
    return false;
  }
  std::string_view digits = t;
  if (digits.front() == '+') digits.remove_prefix(1);  // from_chars rejects a leading '+'
  const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), out);
  if (ec == std::errc::result_out_of_range) {
    why = fmt::format("'{}', out of the range of a double", t);
    return false;
  }
  if (ec != std::errc{} || ptr == digits.data()) {
    why = fmt::format("'{}', not a number", t);
    return false;
  }
  if (ptr != digits.data() + digits.size()) {
    why = fmt::format("'{}', with trailing characters '{}'", t,
                      std::string_view(ptr, digits.data() + digits.size() - ptr));
    return false;
  }
  if (!std::isfinite(out)) {
    why = fmt::format("'{}', which is not finite", t);
    return false;
  }
  return true;
}

// "invalid --lambda: 'log:0.1:30:0' (allowed: n >= 1, got n = 0; a grid is ...)"
const char* domain_text(grid_domain d) {
  return d == grid_domain::positive ? "> 0" : d == grid_domain::non_negative ? ">= 0" : "";
}

[[noreturn]] void grid_error(std::string_view key, std::string_view text, const std::string& rule,
                             const std::string& got, grid_domain d) {
  throw invalid_value(std::string(key), std::string(text),
                      fmt::format("{}, got {}; a grid is {} of finite values{}{}", rule, got,
                                  grid_forms, d == grid_domain::any ? "" : " ",
                                  domain_text(d)));
}

double grid_number(std::string_view key, std::string_view text, std::string_view item,
                   const std::string& what, grid_domain d = grid_domain::positive) {
  double v = 0;
  std::string why;
  if (!to_double(item, v, why)) grid_error(key, text, "finite numbers", what + ": " + why, d);
  const bool ok = d == grid_domain::any || (d == grid_domain::positive ? v > 0.0 : v >= 0.0);
  if (!ok)
    grid_error(key, text, fmt::format("values {}", domain_text(d)), fmt::format("{} = {}", what, v),
               d);
  return v;
}

std::vector<double> parse_range(std::string_view key, std::string_view text, std::string_view t,
                                grid_domain d) {
  const auto parts = split(t, ':');
  const bool log = parts[0] == "log";
  if (parts.size() != 4)
    grid_error(key, text, fmt::format("{}:a:b:n with 4 fields", parts[0]),
               fmt::format("{} fields", parts.size()), d);
  // a log range needs a, b > 0 whatever the parameter allows.
  const grid_domain ends = log ? grid_domain::positive : d;
  const double a = grid_number(key, text, parts[1], "a", ends);
  const double b = grid_number(key, text, parts[2], "b", ends);
  const auto n_text = trim(parts[3]);
  long long n = 0;
  const auto [ptr, ec] = std::from_chars(n_text.data(), n_text.data() + n_text.size(), n);
  if (ec != std::errc{} || n_text.empty() || ptr != n_text.data() + n_text.size())
    grid_error(key, text, "n a whole number", fmt::format("n = '{}'", n_text), d);
  if (n < 1) grid_error(key, text, "n >= 1", fmt::format("n = {}", n), d);
  if (static_cast<unsigned long long>(n) > max_grid_values)
    grid_error(key, text, fmt::format("n <= {}", max_grid_values), fmt::format("n = {}", n), d);

  std::vector<double> values(static_cast<std::size_t>(n));
  values.front() = a;
  if (n == 1) return values;
  const double steps = static_cast<double>(n - 1);
  for (long long i = 1; i < n - 1; ++i) {
    const double f = static_cast<double>(i) / steps;
    // lin: a + (b - a) f;  log: a (b/a)^f = exp(ln a + f (ln b - ln a)).
    values[static_cast<std::size_t>(i)] =
        log ? std::exp(std::log(a) + f * (std::log(b) - std::log(a))) : a + (b - a) * f;
  }
  values.back() = b;  // exact end points, no rounding drift
  return values;
}

std::vector<double> validated_times(std::vector<double> times, std::vector<std::string> where) {
  for (std::size_t i = 1; i < times.size(); ++i)
    if (!(times[i] > times[i - 1]))
      throw invalid_parameter(where[i], times[i],
                              fmt::format("strictly greater than the previous time {}: switch "
                                          "times must be sorted and distinct",
                                          times[i - 1]));
  return times;
}

double switch_time(const std::string& where, std::string_view item) {
  double v = 0;
  std::string why;
  if (!to_double(item, v, why))
    throw invalid_value(where, std::string(trim(item)), "a finite number >= 0; got " + why);
  if (v < 0.0) throw invalid_parameter(where, v, "a finite number >= 0");
  return v;
}

}  // namespace

std::string limit_text(std::uint64_t v) {
  if (v == UINT64_MAX) return fmt::format("2^64 - 1 = {}", v);
  if (v >= (1u << 16) && std::has_single_bit(v))
    return fmt::format("2^{} = {}", std::countr_zero(v), v);
  return fmt::format("{}", v);
}

std::string read_text_file(const std::string& path) {
  // A directory opens as an empty stream and /dev/zero never ends: accept
  // regular files of sane size only.
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (status.type() == std::filesystem::file_type::not_found)
    throw error(exit_code::invalid_input, fmt::format("input file '{}' does not exist", path));
  if (ec) throw io_error(path, ec.message());
  if (!std::filesystem::is_regular_file(status))
    throw error(exit_code::invalid_input,
                fmt::format("input file '{}' is not a regular file", path));
  constexpr std::uintmax_t max_bytes = 64u << 20;
  if (std::filesystem::file_size(path, ec) > max_bytes || ec)
    throw io_error(path, ec ? ec.message() : "larger than 64 MiB");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw io_error(path, std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw io_error(path, "read failed");
  return ss.str();
}

double parse_number(std::string_view key, std::string_view text) {
  double v = 0;
  std::string why;
  if (!to_double(text, v, why))
    throw invalid_value(std::string(key), std::string(text), "a finite number; got " + why);
  return v;
}

std::uint64_t parse_unsigned(std::string_view key, std::string_view text, std::uint64_t min,
                             std::uint64_t max) {
  const auto t = trim(text);
  std::uint64_t v = 0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  const auto allowed = fmt::format("a whole number from {} to {}", min, limit_text(max));
  if (t.empty() || ec != std::errc{} || ptr != t.data() + t.size() || v < min || v > max)
    throw invalid_value(std::string(key), std::string(text), allowed);
  return v;
}

bool is_single_value(std::string_view text) noexcept {
  text = trim(text);
  return !text.empty() && text.find(',') == std::string_view::npos && text.find(':') == std::string_view::npos;
}

grid_domain grid_domain_of(std::string_view symbol) {
  switch (domain_of(symbol)) {
    case parameter_domain::non_negative: return grid_domain::non_negative;
    case parameter_domain::any: return grid_domain::any;
    default: return grid_domain::positive;  // mu_s, mu_k: a grid gives them values
  }
}

void order_added_axes(std::vector<axis>& axes) {
  // The leading axes (lambda, mu) first, in that order; the rest as given.
  const auto rank = [](const axis& a) { return std::min(axis_rank(a.name), leading_axis_count); };
  std::stable_sort(axes.begin(), axes.end(),
                   [&](const axis& a, const axis& b) { return rank(a) < rank(b); });
}

std::vector<double> parse_grid(std::string_view key, std::string_view text, grid_domain d) {
  const auto t = trim(text);
  if (t.empty()) grid_error(key, text, "at least one value", "an empty list", d);
  if (t.starts_with("lin:") || t.starts_with("log:")) return parse_range(key, text, t, d);
  if (t.find(':') != std::string_view::npos)
    grid_error(key, text, "a range 'lin:a:b:n' or 'log:a:b:n'", "another prefix", d);
  std::vector<double> values;
  const auto items = split(t, ',');
  if (items.size() > max_grid_values)
    grid_error(key, text, fmt::format("at most {} values", max_grid_values),
               fmt::format("{}", items.size()), d);
  for (std::size_t i = 0; i < items.size(); ++i)
    values.push_back(grid_number(key, text, items[i], fmt::format("entry #{}", i + 1), d));
  return values;
}

switch_schedule parse_switch_schedule(std::string_view text, std::string_view origin,
                                      std::size_t level_count) {
  switch_schedule out;
  std::vector<std::string> where;
  std::size_t line_no = 0, with_level = 0;
  for (auto line : split(text, '\n')) {
    ++line_no;
    if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    line = trim(line);
    if (line.empty()) continue;
    const auto gap = line.find_first_of(" \t");
    const auto time_text = line.substr(0, gap);
    where.push_back(fmt::format("switch time at {}:{}", origin, line_no));
    out.times.push_back(switch_time(where.back(), time_text));
    if (gap == std::string_view::npos) continue;
    const std::string level_where = fmt::format("belt level at {}:{}", origin, line_no);
    const auto level_text = trim(line.substr(gap));
    const std::uint64_t level =
        parse_unsigned(level_where, level_text, 1, std::max<std::size_t>(level_count, 1));
    out.levels.resize(out.times.size() - 1, 0);  // marks lines without a level (checked below)
    out.levels.push_back(static_cast<std::size_t>(level - 1));
    ++with_level;
  }
  if (with_level > 0 && with_level != out.times.size())
    throw invalid_value(fmt::format("switch lines of {}", origin),
                        fmt::format("{} of {} lines with a level", with_level, out.times.size()),
                        "every line 't level', or every line 't' (two levels: go to the other one)");
  if (with_level == 0 && level_count > 2 && !out.times.empty())
    throw invalid_value(fmt::format("switch lines of {}", origin), "lines 't' without a level",
                        fmt::format("lines 't level' (level 1..{}): the belt has {} levels",
                                    level_count, level_count));
  out.times = validated_times(std::move(out.times), std::move(where));
  return out;
}

switch_schedule read_switch_schedule_file(const std::string& path, std::size_t level_count) {
  return parse_switch_schedule(read_text_file(path), path, level_count);
}

std::vector<double> parse_switch_times(std::string_view text, std::string_view origin) {
  return parse_switch_schedule(text, origin, 2).times;
}

std::vector<double> read_switch_times_file(const std::string& path) {
  return parse_switch_times(read_text_file(path), path);
}

int parse_belt_start(std::string_view key, std::string_view text, std::size_t level_count) {
  const auto t = trim(text);
  const std::string allowed =
      level_count == 2 ? "+1 (first level), -1 (second level) or stationary"
                       : fmt::format("a level number 1..{}, or stationary", level_count);
  if (t == "stationary" || t == "random") return 0;
  if (t == "-1" && level_count == 2) return -1;
  if (t == "+1") return 1;
  std::uint64_t v = 0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (t.empty() || ec != std::errc{} || ptr != t.data() + t.size() || v < 1 ||
      v > (level_count == 2 ? 1 : level_count))
    throw invalid_value(std::string(key), std::string(text), allowed);
  return static_cast<int>(v);
}

std::string belt_start_text(int belt_start) {
  if (belt_start == 0) return "stationary";
  if (belt_start == 1) return "+1";
  return fmt::format("{}", belt_start);
}

std::vector<double> parse_value_list(std::string_view key, std::string_view text) {
  std::vector<double> values;
  const auto items = split(trim(text), ',');
  for (std::size_t i = 0; i < items.size(); ++i)
    values.push_back(parse_number(fmt::format("{} entry #{}", key, i + 1), items[i]));
  return values;
}

std::vector<double> parse_belt_levels(std::string_view text) {
  auto levels = parse_value_list("--belt-levels", text);
  if (levels.size() < 2)
    throw invalid_parameter("--belt-levels (count)", static_cast<double>(levels.size()),
                            "at least 2 levels");
  return levels;
}

std::vector<double> parse_belt_generator(std::string_view text) {
  std::vector<double> q;
  std::size_t rows = 0, start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(';', start), text.size());
    const auto row =
        parse_value_list(fmt::format("--belt-generator row {}", rows + 1), text.substr(start, end - start));
    q.insert(q.end(), row.begin(), row.end());
    ++rows;
    start = end + 1;
  }
  if (q.size() != rows * rows)
    throw invalid_value("--belt-generator", std::string(text),
                        fmt::format("a square matrix: {} rows need {} rates each", rows, rows));
  return q;
}

std::vector<double> parse_switch_time_list(std::string_view key, std::string_view text) {
  std::vector<double> times;
  std::vector<std::string> where;
  if (trim(text).empty()) return times;
  const auto items = split(text, ',');
  for (std::size_t i = 0; i < items.size(); ++i) {
    where.push_back(fmt::format("{} entry #{}", key, i + 1));
    times.push_back(switch_time(where.back(), items[i]));
  }
  return validated_times(std::move(times), std::move(where));
}

sweep_engine parse_engine(std::string_view key, std::string_view text) {
  if (text == "fast") return sweep_engine::fast;
  if (text == "reference") return sweep_engine::reference;
  throw invalid_value(std::string(key), std::string(text), "fast or reference");
}

void parse_target_ci(std::string_view key, std::string_view text, sweep_spec& s) {
  const auto colon = text.rfind(':');
  if (colon == std::string_view::npos || colon == 0)
    throw invalid_value(std::string(key), std::string(text),
                        "STAT:HALFWIDTH, e.g. R:0.002 (a statistic and the 95% half-width of "
                        "its mean)");
  sweep_spec t;
  t.target_statistic = std::string(text.substr(0, colon));
  try {
    (void)target_quantity(t);  // throws for an unknown statistic
  } catch (const error& e) {
    throw error(e.code(), fmt::format("{} {}: {}", key, text, e.what()));
  }
  const double h = parse_number(key, text.substr(colon + 1));
  if (!(h > 0.0) || !std::isfinite(h))
    throw invalid_parameter(std::string(key) + " half-width", h, "finite and > 0");
  s.target_statistic = t.target_statistic;
  s.target_halfwidth = h;
}

}  // namespace stickslip::io
