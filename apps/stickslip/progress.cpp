#include "progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace stickslip::app {

const char* format_duration(double seconds, char (&buf)[32]) noexcept {
  if (!std::isfinite(seconds) || seconds < 0) seconds = 0;
  const auto s = static_cast<long long>(std::llround(seconds));
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%lld:%02lld:%02lld", s / 3600, s / 60 % 60, s % 60);
  else if (s >= 60)
    std::snprintf(buf, sizeof buf, "%lld:%02lld", s / 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%llds", s);
  return buf;
}

progress_bar::progress_bar(bool enabled) : active_(enabled && ::isatty(STDERR_FILENO) == 1) {}

progress_bar::~progress_bar() { finish(); }

work_meter::work_meter(const sweep_spec& s, const std::function<bool(const work_unit&)>& to_run)
    : spec_(&s) {
  per_realization_.resize(point_count(s));
  for (std::size_t i = 0; i < per_realization_.size(); ++i)
    per_realization_[i] = expected_events(point_parameters(s, i));
  for (std::uint64_t i = 0, n = unit_count(s); i < n; ++i)
    if (const auto u = unit_at(s, i); to_run(u)) total_ += cost(u);
}

double work_meter::cost(const work_unit& u) const noexcept {
  const std::uint64_t first = u.block * spec_->block_size;
  const std::uint64_t last = std::min(spec_->realizations, first + spec_->block_size);
  return static_cast<double>(last - first) * per_realization_[u.point];
}

void work_meter::add(const work_unit& u) noexcept { done_ += cost(u); }

double eta_seconds(double elapsed, double work_done) noexcept {
  if (!(work_done > 0)) return -1;
  return elapsed * std::max(0.0, 1.0 - work_done) / work_done;
}

void progress_bar::update(std::uint64_t done, std::uint64_t total, double work_done) {
  if (!active_ || total == 0) return;
  const auto now = clock::now();
  if (done < total && drawn_ && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  drawn_ = true;
  const double fraction = std::clamp(work_done, 0.0, 1.0);  // of the expected work
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  constexpr int width = 30;
  const int filled = static_cast<int>(fraction * width);
  char e[32], r[32];
  const char* elapsed_text = format_duration(elapsed, e);
  const double left = eta_seconds(elapsed, work_done);
  const char* eta = left >= 0 ? format_duration(left, r) : "?";
  fmt::print(stderr, "\r[{}{}] {:5.1f}% of the work, {}/{} units, {} elapsed, ETA {}  ",
             std::string(static_cast<std::size_t>(filled), '#'),
             std::string(static_cast<std::size_t>(width - filled), '.'), 100.0 * fraction, done,
             total, elapsed_text, eta);
  std::fflush(stderr);
}

void progress_bar::finish() {
  if (drawn_) {
    fmt::print(stderr, "\n");
    drawn_ = false;
  }
}

}  // namespace stickslip::app
