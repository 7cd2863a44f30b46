// The peak searches of `reproduce` (study::peak_locator): each runs its
// sweeps on the command's runner, so under mpirun every rank works on them,
// and once finished it is kept in OUT/.runs/<id>.peak, so a reproduce that is
// killed and resumed does not search again. A search in progress is not
// journaled: at the study's targets it takes seconds, and its result depends
// only on the request, so a resume repeats it exactly.
#pragma once
#include <functional>
#include <string>

#include "stickslip/run/runner.hpp"
#include "stickslip/run/stop.hpp"
#include "stickslip/study/design.hpp"

namespace stickslip::app {

// `log` is told when a kept search is used instead of running it again.
[[nodiscard]] study::peak_locator kept_peak_locator(
    std::string runs_dir, run::runner& r, const run::stop_token& stop,
    std::function<void(const std::string&)> log = {});

// The text kept for a finished search and its reading (exposed for tests):
// `request` identifies the search (fingerprint of the spec, which includes the
// build, and every option); read_kept_peak returns false when the text is not
// a search for `request`.
[[nodiscard]] std::string describe_request(const precision::sweep_peak_request& q);
[[nodiscard]] std::string kept_peak_text(const std::string& request,
                                         const precision::peak_result& p);
[[nodiscard]] bool read_kept_peak(const std::string& text, const std::string& request,
                                  precision::peak_result& p);

}  // namespace stickslip::app
