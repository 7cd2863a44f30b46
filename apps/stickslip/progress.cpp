#include "progress.hpp"

#include "stickslip/run/work_meter.hpp"

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
  const double left = run::eta_seconds(elapsed, work_done);
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
