// The values an uncertain realization draws (parameter_law.hpp), each a pure
// function of (seed, point key, realization, substream, index):
//   uncertain parameter i (in the order given) uses word `offset + i` of the
//   realization's substream `uncertain_parameters` (random_stream.hpp);
//   a sweep draws with offset 0; a sensitivity design draws its sample A
//   with offset 0 and its sample B with offset d (d = number of laws).
// With common random numbers the key is common_stream_key, as for every
// other draw, so realization r of every grid point draws the same u's.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "stickslip/parameters.hpp"
#include "stickslip/uncertainty/parameter_law.hpp"

namespace stickslip {

// The uniforms u_i in (0, 1) of words [offset, offset + count) of
// realization r's uncertain-parameter substream.
[[nodiscard]] std::vector<double> uncertain_uniforms(std::uint64_t seed, std::uint64_t key,
                                                     std::uint64_t realization, std::size_t offset,
                                                     std::size_t count);

// The parameters of one realization: `base` with each uncertain parameter set
// to values[i] (set_parameter, in the order of `laws`); draw_values gives
// values[i] = quantile(law_i, u_i) of realization r's uniforms.
[[nodiscard]] model_parameters with_values(const model_parameters& base,
                                           std::span<const uncertain_parameter> laws,
                                           std::span<const double> values);
[[nodiscard]] std::vector<double> draw_values(std::span<const uncertain_parameter> laws,
                                              std::uint64_t seed, std::uint64_t key,
                                              std::uint64_t realization, std::size_t offset = 0);

// The smallest and the largest value a draw can take: the quantiles of the
// smallest and the largest open uniform (random_stream::open_uniform).
[[nodiscard]] double smallest_draw(const parameter_law& law);
[[nodiscard]] double largest_draw(const parameter_law& law);

// `base` with each uncertain parameter at its law's median (quantile 0.5),
// in the paper's form when that is the paper's model (paper_form): what a
// point with laws stands for where one model is needed, namely its
// coordinates in outputs, the histogram ranges of its statistics, and the
// cost model of the ETA (expected_events). Realizations never run it.
[[nodiscard]] model_parameters with_medians(const model_parameters& base,
                                            std::span<const uncertain_parameter> laws);

// The recorded parameters (recorded_parameter_names) a law sets, which
// therefore have no single value: each law's symbol, and mu_s and mu_k when
// mu has a law (they resolve to it). Writers leave them out of the values
// of the base and name the laws instead.
[[nodiscard]] std::vector<std::string> symbols_set_by_laws(
    std::span<const uncertain_parameter> laws);

// The stream key of a grid point whose parameters include laws: point_key of
// `base` mixed with the canonical text of every law, so that two points
// differing only in a law get different streams, and the key does not depend
// on the base values of the uncertain symbols.
[[nodiscard]] std::uint64_t uncertain_point_key(const model_parameters& base,
                                                std::span<const uncertain_parameter> laws) noexcept;

}  // namespace stickslip
