#include "run_wiring.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstdio>

#include "commands.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/io/output_files.hpp"

namespace stickslip::app {

void wire_run_plan(run::run_plan& plan, const std::string& checkpoint_interval,
                   const run::stop_token& stop, progress_bar& bar) {
  const double interval = io::parse_number("--checkpoint-interval", checkpoint_interval);
  if (!(interval >= 0) || interval > 86400)
    throw invalid_parameter("--checkpoint-interval", interval, "0 .. 86400 seconds");
  plan.checkpoint_interval = std::chrono::duration<double>(interval);
  plan.stop = &stop;
  plan.report = [](const std::string& line) {
    fmt::print(stderr, "stickslip: journal: {}\n", line);
  };
  if (bar.active())
    plan.progress = [&bar](std::uint64_t d, std::uint64_t total, double work) {
      bar.update(d, total, work);
    };
}

void end_failed_run(const error& e, progress_bar& bar, execution& exec) {
  bar.finish();
  if (e.code() == exit_code::io_failure) {
    exec.release();  // std::_Exit skips the destructors: let the MPI workers return first
    exit_after_failed_write(e);
  }
  throw;
}

void note_removed_outputs(const std::vector<std::string>& removed) {
  if (const auto note = io::removed_outputs_note(removed); !note.empty())
    fmt::print(stderr, "stickslip: note: {}\n", note);
}

}  // namespace stickslip::app
