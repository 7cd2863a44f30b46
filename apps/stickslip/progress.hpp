// A small progress bar with an ETA on stderr, drawn with '\r' and only when
// stderr is a terminal (bookworm packages no C++ progress-bar library).
// Plug it into sweep_hooks::progress; calls are serialized by the sweep.
// The ETA extrapolates from the fraction of the expected work done
// (run::work_meter, expected_unit_cost), not from the unit count: the costliest
// units run first, so a count-based ETA starts far too high.
#pragma once
#include <chrono>
#include <cstdint>

namespace stickslip::app {

class progress_bar {
 public:
  // Draws only if `enabled` and stderr is a terminal.
  explicit progress_bar(bool enabled = true);
  progress_bar(const progress_bar&) = delete;
  progress_bar& operator=(const progress_bar&) = delete;
  ~progress_bar();

  // At most ~10 redraws per second, and always the last one. `work_done`
  // is the fraction of the expected work finished (0 .. 1).
  void update(std::uint64_t done, std::uint64_t total, double work_done);
  // Ends the bar's line (if one was drawn).
  void finish();
  [[nodiscard]] bool active() const noexcept { return active_; }

 private:
  using clock = std::chrono::steady_clock;
  bool active_;
  bool drawn_ = false;
  clock::time_point start_ = clock::now();
  clock::time_point last_draw_{};
};

// "1:02:03", "4:05" or "7s".
[[nodiscard]] const char* format_duration(double seconds, char (&buf)[32]) noexcept;

}  // namespace stickslip::app
