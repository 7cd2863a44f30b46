#include <fmt/format.h>

#include "stickslip/error.hpp"
#include "writers_detail.hpp"

namespace stickslip::io::detail {

const std::vector<statistic_info>& statistics_table() {
  static const std::vector<statistic_info> t{
      {"R", "stick_fraction", &point_statistics::stick_fraction, "1", "stick fraction R",
       "total stick time in [0, t_a] divided by t_a, one value per realization",
       "realizations"},
      {"sticks_per_time", "sticks_per_time", &point_statistics::sticks_per_time, "1/s",
       "stick rate S_T/t_a",
       "number of sticks of positive length beginning in [0, t_a) (a stick cut off by t_a "
       "counts), divided by t_a, one value per realization",
       "realizations"},
      {"slips_per_time", "slips_per_time", &point_statistics::slips_per_time, "1/s",
       "slip rate S_L/t_a",
       "number of slips beginning after the first stick (the slip before the first stick is "
       "not counted), divided by t_a, one value per realization",
       "realizations"},
      {"stick_duration", "stick_duration", &point_statistics::stick_duration, "s",
       "stick duration D",
       "duration D_i of every stick, pooled over all sticks of all realizations (a stick cut "
       "off by t_a enters clipped)",
       "sticks, over all realizations"},
      {"first_stick_duration", "first_stick_duration", &point_statistics::first_stick_duration,
       "s", "first stick duration D_1",
       "duration of the first stick, over the realizations that have a stick (see "
       "no_stick_count); it may be censored by t_a (see first_stick_censored_count)",
       "realizations with at least one stick"},
      {"slip_duration", "slip_duration", &point_statistics::slip_duration, "s",
       "slip duration H",
       "duration H_i of every counted slip (those beginning after the first stick), pooled "
       "over all realizations",
       "counted slips, over all realizations"},
  };
  return t;
}

const std::vector<histogram_info>& histograms_table() {
  static const std::vector<histogram_info> t{
      {"stick_fraction", &point_statistics::stick_fraction_hist, "1", "1", "stick fraction R"},
      {"stick_duration", &point_statistics::stick_duration_hist, "s", "1/s",
       "stick duration D"},
      {"first_stick_duration", &point_statistics::first_stick_duration_hist, "s", "1/s",
       "first stick duration D_1"},
      {"slip_duration", &point_statistics::slip_duration_hist, "s", "1/s", "slip duration H"},
  };
  return t;
}

std::vector<std::string> swept_symbols(const sweep_spec& s) {
  std::vector<std::string> out;
  for (const auto& ax : s.axes) out.emplace_back(info_for(ax.name).symbol);
  return out;
}

std::vector<std::string> point_parameter_symbols(const sweep_spec& s) {
  std::vector<std::string> out{"lambda", "mu"};
  for (auto& sym : swept_symbols(s))
    if (sym != "lambda" && sym != "mu") out.push_back(sym);
  return out;
}

std::string parameter_variable_name(const std::string& symbol) {
  std::string n = info_for(symbol).long_name;
  for (auto& c : n)
    if (c == '-') c = '_';
  return n;
}

void check_shape(const result_set& rs) {
  const auto n = point_count(rs.spec);
  if (rs.points.size() != n)
    throw error(exit_code::internal,
                fmt::format("result set holds {} points but its grid has {}", rs.points.size(), n));
  // Writers lay points out in this order (row-major over the axes).
  for (std::size_t i = 0; i < n; ++i)
    if (rs.points[i].index != point_index(rs.spec, i))
      throw error(exit_code::internal,
                  fmt::format("result set point {} is not at its grid position", i));
  if (rs.spec.keep_records && !rs.records.empty() && rs.records.size() != n)
    throw error(exit_code::internal,
                fmt::format("result set holds records of {} points but its grid has {}",
                            rs.records.size(), n));
}

}  // namespace stickslip::io::detail
