// What `sweep` and `sensitivity` (every command that runs through
// run::sweep_into) wire the same way: --checkpoint-interval, the stop token,
// journal notes on stderr and the progress bar; and a failure's ending.
#pragma once
#include <string>
#include <vector>

#include "execution.hpp"
#include "progress.hpp"
#include "stickslip/error.hpp"
#include "stickslip/run/journaled_run.hpp"

namespace stickslip::app {

// Sets plan.checkpoint_interval (the flag's text, 0 .. 86400 s), plan.stop,
// plan.report (one "stickslip: journal: ..." line each) and, when `bar` is
// shown, plan.progress. `bar` and `stop` must outlive the run.
void wire_run_plan(run::run_plan& plan, const std::string& checkpoint_interval,
                   const run::stop_token& stop, progress_bar& bar);

// In a catch block around the run: ends the bar; an output that failed to
// write leaves through exit_after_failed_write (after releasing the MPI
// workers); anything else is rethrown.
[[noreturn]] void end_failed_run(const error& e, progress_bar& bar, execution& exec);

// One "stickslip: note:" line naming the outputs of an earlier run that
// write_all removed because this run does not write them (--overwrite, or a
// resume of a run started with it) and that are still gone
// (io::removed_outputs_note: call it after the last output is written);
// nothing when there are none.
void note_removed_outputs(const std::vector<std::string>& removed);

}  // namespace stickslip::app
