// The building blocks shared by the peak finders that evaluate a stage in G
// independent groups (find_peak_common, find_peak_score): the mean curve of
// the groups, the least-squares polynomial of it with the batch-means
// covariance of its coefficients, the scan's check that the highest point is
// interior, and how many groups a frozen window adds. No I/O.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "stickslip/precision/local_fit.hpp"
#include "stickslip/precision/peak_finder.hpp"

namespace stickslip::precision {

// rows[g][i]: group g's value at point i. The mean over the groups per point.
[[nodiscard]] std::vector<double> mean_curve(const std::vector<std::vector<double>>& rows);

// The least-squares polynomial (in t = (x - center)/scale, every point
// weighted equally) of the groups' mean curve, with the covariance of its
// coefficients from the spread of the groups' fits: the fit is linear in the
// data, so the mean of the groups' coefficients is the fit of the mean curve,
// and its covariance is theirs over G (batch means: the groups are
// independent replicates, whatever the correlation between the points).
[[nodiscard]] polynomial_fit fit_groups(const std::vector<double>& xs,
                                        const std::vector<std::vector<double>>& rows,
                                        std::size_t degree, double center, double scale);

// The polynomial whose coefficients are the mean of the groups' (coefs[g]
// in t = (x - center)/scale), with their batch-means covariance: what
// fit_groups does after fitting each group.
[[nodiscard]] polynomial_fit average_of_groups(const std::vector<std::vector<double>>& coefs,
                                               double center, double scale);

// What both group finders record of a stage with an estimate (r.argmax,
// its interval and r.max set): the maximum's interval r.max +- max_halfwidth,
// the window and its point count, and the progress report's estimate.
void record_stage_estimate(peak_result& r, peak_stage& progress, double max_halfwidth,
                           double window_lo, double window_hi, std::size_t points) noexcept;

// The realizations per point of the next window: `want`, but at least n and
// at most 8n (8n when want is not finite).
[[nodiscard]] std::uint64_t grown_realizations(std::uint64_t n, double want) noexcept;

// The index of the highest mean of the first scan; throws stickslip::error
// (invalid_input) when it is at an end of the range, where the maximizer
// may lie outside.
[[nodiscard]] std::size_t interior_scan_maximum(const std::vector<double>& xs,
                                                const std::vector<double>& means,
                                                const peak_options& o);

// The groups a frozen window adds when `have` groups give a sampling part
// `ratio` times the one aimed at (~ 1/sqrt(groups)): what that needs, but at
// least half and at most 3x the groups so far (few looks at the data keep
// the stop rule from favouring an error estimate that is small by chance:
// optional stopping), and at least up to `min_groups_to_stop` (the next look
// must be able to stop).
[[nodiscard]] std::size_t groups_to_add(std::size_t have, double ratio,
                                        std::size_t min_groups_to_stop) noexcept;

}  // namespace stickslip::precision
