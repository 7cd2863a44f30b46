// The statistics schema (statistics_schema.hpp): its rows against the paper's
// list of statistics (Sec. 4, docs/model.md), point_statistics::add against
// the definitions on hand-made realizations, and the merge algebra of every
// row (halves merged equal everything filled at once).
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "stickslip/record_schema.hpp"
#include "stickslip/serial_bytes.hpp"
#include "stickslip/statistics.hpp"
#include "stickslip/statistics_schema.hpp"

namespace stickslip {
namespace {

const std::vector<std::uint32_t> no_jumps;  // two-level belts: not counted

// Written from the paper (Sec. 4) and docs/outputs.md, not from the table.
struct expected_quantity {
  std::string name, symbol, units;
  histogram_range range;
};
const std::vector<expected_quantity> paper = {
    {"stick_fraction", "R", "1", histogram_range::unit_interval},
    {"sticks_per_time", "S_T/t_a", "1/s", histogram_range::none},
    {"slips_per_time", "S_L/t_a", "1/s", histogram_range::none},
    {"stick_duration", "D", "s", histogram_range::stick_duration},
    {"first_stick_duration", "D_1", "s", histogram_range::stick_duration},
    {"slip_duration", "H", "s", histogram_range::slip_duration},
    // The model family's, after the paper's.
    {"stick_onset_position", "X", "m", histogram_range::stick_band},
    {"friction_power", "W_f", "W", histogram_range::none},
    {"damping_power", "W_c", "W", histogram_range::none},
};

TEST(StatisticsSchema, ListsThePapersStatisticsInOrder) {
  const auto q = quantities();
  ASSERT_EQ(q.size(), paper.size());
  for (std::size_t i = 0; i < q.size(); ++i) {
    EXPECT_EQ(q[i].name, paper[i].name);
    EXPECT_EQ(q[i].symbol, paper[i].symbol) << paper[i].name;
    EXPECT_EQ(q[i].units, paper[i].units) << paper[i].name;
    EXPECT_EQ(q[i].range, paper[i].range) << paper[i].name;
    EXPECT_EQ(q[i].density != nullptr, paper[i].range != histogram_range::none) << paper[i].name;
    EXPECT_EQ(q[i].value != nullptr, per_realization(q[i].sampled)) << paper[i].name;
  }
  std::vector<std::string> names;
  for (const auto& c : counters()) names.emplace_back(c.name);
  EXPECT_EQ(names, (std::vector<std::string>{"no_stick_count", "first_stick_censored_count",
                                             "belt_switches", "stick_onsets", "stick_breaks",
                                             "slip_reversals"}));
}

// Every name a writer derives from the table is distinct, and every long_name
// fits one line of an xarray plot label (30 characters with " [units]").
TEST(StatisticsSchema, OutputNamesAreDistinctAndLabelsShort) {
  std::set<std::string> nc_names{"realizations"}, summary_names{"realizations"};
  for (const auto& q : quantities()) {
    for (const char* suffix : {"_mean", "_std", "_ci95_low", "_ci95_high", "_count"})
      EXPECT_TRUE(nc_names.insert(std::string(q.name) + suffix).second) << q.name << suffix;
    if (q.density) {
      for (const char* suffix : {"_density", "_counts", "_bin", "_bin_bounds", "_bin_low",
                                 "_bin_high", "_underflow", "_overflow"})
        EXPECT_TRUE(nc_names.insert(std::string(q.name) + suffix).second) << q.name << suffix;
    }
    EXPECT_TRUE(summary_names.insert(q.summary_name).second) << q.summary_name;
    EXPECT_LE(std::string("mean ").size() + std::string(q.long_name).size() + 3 +
                  std::string(q.units).size(),
              30u)
        << q.name;
    EXPECT_FALSE(std::string(q.description).empty()) << q.name;
  }
  for (const auto& c : counters()) {
    EXPECT_TRUE(nc_names.insert(c.name).second) << c.name;
    EXPECT_TRUE(summary_names.insert(c.summary_name).second) << c.summary_name;
    EXPECT_LE(std::string(c.long_name).size() + 4, 30u) << c.name;
  }
  EXPECT_NE(statistics_schema_id(), 0u);
  EXPECT_EQ(statistics_schema_id(), statistics_schema_id());
}

// m = 1, g = 10, mu = 1, k = 10, V = 1: a = 1, d_max = 2; lambda = 1, t_a = 10:
// the slip histogram covers [0, min(10, 5 / 1)] = [0, 5].
model_parameters unit_band() {
  model_parameters p;
  p.mass = 1;
  p.gravity = 10;
  p.friction_coefficient = 1;
  p.stiffness = 10;
  p.belt_speed = 1;
  p.switch_rate = 1;
  p.window = 10;
  return p;
}

TEST(StatisticsSchema, HistogramRangesFollowTheRules) {
  histogram_spec h;
  h.bins = 4;
  const point_statistics s(unit_band(), h);
  EXPECT_EQ(s.stick_fraction_hist.hi(), 1.0);
  EXPECT_EQ(s.stick_duration_hist.hi(), 2.0);
  EXPECT_EQ(s.first_stick_duration_hist.hi(), 2.0);
  EXPECT_EQ(s.slip_duration_hist.hi(), 5.0);
  h.stick_duration_max = 3;
  h.slip_duration_max = 7;
  const point_statistics t(unit_band(), h);
  EXPECT_EQ(t.stick_duration_hist.hi(), 3.0);
  EXPECT_EQ(t.slip_duration_hist.hi(), 7.0);
  EXPECT_EQ(t.stick_duration_hist.bins(), 4u);
}

TEST(StatisticsSchema, AddFollowsTheDefinitions) {
  histogram_spec h;
  h.bins = 4;
  point_statistics s(unit_band(), h);
  realization_record a;
  a.sticks = 3;
  a.slips = 2;
  a.stick_fraction = 0.35;
  a.first_stick_duration = 0.5;
  a.first_stick_censored = true;
  a.events = {5, 3, 2, 1};
  a.friction_power = 3.0;
  a.damping_power = 0.5;
  const std::vector<double> a_sticks{0.5, 1.0, 2.0}, a_slips{0.25, 0.75},
      a_onsets{-0.9, 0.1, 0.6}, a_levels{0.75, 0.25};
  s.add({a, a_sticks, a_slips, a_onsets, a_levels, no_jumps}, 10.0);
  realization_record b;  // no stick at all
  b.stick_fraction = 0.0;
  b.events = {4, 0, 0, 6};
  b.friction_power = 1.0;
  const std::vector<double> none, b_levels{0.25, 0.75};
  s.add({b, none, none, none, b_levels, no_jumps}, 10.0);

  EXPECT_EQ(s.realizations, 2u);
  EXPECT_EQ(s.stick_fraction.count(), 2u);
  EXPECT_DOUBLE_EQ(s.stick_fraction.mean(), 0.175);
  EXPECT_DOUBLE_EQ(s.sticks_per_time.mean(), 0.15);  // (3/10 + 0) / 2
  EXPECT_DOUBLE_EQ(s.slips_per_time.mean(), 0.1);    // (2/10 + 0) / 2
  EXPECT_EQ(s.stick_duration.count(), 3u);
  EXPECT_DOUBLE_EQ(s.stick_duration.mean(), 3.5 / 3);
  EXPECT_EQ(s.first_stick_duration.count(), 1u);  // only realizations with a stick
  EXPECT_EQ(s.first_stick_duration.mean(), 0.5);
  EXPECT_EQ(s.slip_duration.count(), 2u);
  EXPECT_EQ(s.slip_duration.mean(), 0.5);
  EXPECT_EQ(s.no_stick, 1u);
  EXPECT_EQ(s.first_stick_censored, 1u);
  EXPECT_EQ(s.events, (event_counts{9, 3, 2, 7}));
  // Bins of width 0.25 (R), 0.5 (D, D_1; the last one closed), 1.25 (H).
  EXPECT_EQ(s.stick_fraction_hist.counts(), (std::vector<std::uint64_t>{1, 1, 0, 0}));
  EXPECT_EQ(s.stick_duration_hist.counts(), (std::vector<std::uint64_t>{0, 1, 1, 1}));
  EXPECT_EQ(s.first_stick_duration_hist.counts(), (std::vector<std::uint64_t>{0, 1, 0, 0}));
  EXPECT_EQ(s.slip_duration_hist.counts(), (std::vector<std::uint64_t>{2, 0, 0, 0}));
  // The family's rows: X pooled over sticks on the band [-a, a] = [-1, 1],
  // W_f and W_c per realization, P per level, (D, X) jointly per stick.
  EXPECT_EQ(s.stick_onset_position.count(), 3u);
  EXPECT_DOUBLE_EQ(s.stick_onset_position.mean(), -0.2 / 3);
  EXPECT_EQ(s.stick_onset_position_hist.lo(), -unit_band().band_half_width());
  EXPECT_EQ(s.stick_onset_position_hist.counts(), (std::vector<std::uint64_t>{1, 0, 1, 1}));
  EXPECT_EQ(s.friction_power.mean(), 2.0);
  EXPECT_EQ(s.damping_power.mean(), 0.25);
  ASSERT_EQ(s.level_fraction.size(), 2u);
  EXPECT_EQ(s.level_fraction[0].mean(), 0.5);
  EXPECT_EQ(s.level_fraction[1].count(), 2u);
  EXPECT_EQ(s.stick_duration_onset.total(), 3u);
  // (D, X) = (0.5, -0.9), (1, 0.1), (2, 0.6): D bins of 0.5 (the last closed), X bins of 0.5
  EXPECT_EQ(s.stick_duration_onset.count(1, 0), 1u);
  EXPECT_EQ(s.stick_duration_onset.count(2, 2), 1u);
  EXPECT_EQ(s.stick_duration_onset.count(3, 3), 1u);
}

// A deterministic but irregular realization i.
void add_realization(point_statistics& s, std::uint64_t i) {
  realization_record r;
  r.realization = i;
  r.sticks = static_cast<std::uint32_t>(i % 4);
  r.slips = static_cast<std::uint32_t>(i % 3);
  r.stick_fraction = static_cast<double>(i % 7) / 7.0;
  r.first_stick_duration = 0.1 + static_cast<double>(i % 5) * 0.3;
  r.first_stick_censored = i % 6 == 1;
  r.events = {i % 11, i % 4, i % 3, i % 2};
  r.friction_power = 0.5 + static_cast<double>(i % 9);
  r.damping_power = 0.1 * static_cast<double>(i % 5);
  std::vector<double> sticks, slips, onsets;
  for (std::uint32_t k = 0; k < r.sticks; ++k) sticks.push_back(0.05 + 0.4 * k + 0.01 * i);
  for (std::uint32_t k = 0; k < r.sticks; ++k) onsets.push_back(-1.2 + 0.3 * k + 0.007 * i);
  for (std::uint32_t k = 0; k < r.slips; ++k) slips.push_back(0.3 * k + 0.02 * i);
  const double f = static_cast<double>(i % 13) / 13.0;
  const std::vector<double> levels{f, 1.0 - f};
  s.add({r, sticks, slips, onsets, levels, no_jumps}, 10.0);
}

TEST(StatisticsSchema, EveryRowMergesLikeFillingEverything) {
  histogram_spec h;
  h.bins = 8;
  point_statistics all(unit_band(), h), first(unit_band(), h), second(unit_band(), h);
  for (std::uint64_t i = 0; i < 200; ++i) add_realization(all, i);
  for (std::uint64_t i = 0; i < 90; ++i) add_realization(first, i);
  for (std::uint64_t i = 90; i < 200; ++i) add_realization(second, i);
  first += second;
  EXPECT_EQ(first.realizations, all.realizations);
  for (const auto& q : quantities()) {
    const auto &m = first.*q.moments, &w = all.*q.moments;
    EXPECT_EQ(m.count(), w.count()) << q.name;
    EXPECT_NEAR(m.mean(), w.mean(), 1e-12 * (1 + std::abs(w.mean()))) << q.name;
    EXPECT_NEAR(m.variance(), w.variance(), 1e-10 * (1 + w.variance())) << q.name;
    if (q.density) {
      EXPECT_EQ(first.*q.density, all.*q.density) << q.name;
    }
  }
  for (const auto& c : counters()) {
    EXPECT_EQ(c.value(first), c.value(all)) << c.name;
    EXPECT_GT(c.value(all), 0u) << c.name;  // the realizations exercise every counter
  }
}

// The record layout's identity (part of the serialized layout id) tells
// apart tables that lay out a record's bytes differently: another name,
// another type of member, another order. The same table gives the same id.
TEST(RecordSchema, LayoutIdChangesWithANameATypeOrTheOrder) {
  auto table = record_table;
  const std::uint64_t id = record_layout_id(table);
  EXPECT_EQ(record_layout_id(table), id);
  auto renamed = table;
  renamed[4].name = "stick_count";
  EXPECT_NE(record_layout_id(renamed), id);
  auto retyped = table;  // sticks (u32) read as a double member of the same name
  ASSERT_EQ(std::string(retyped[4].name), "sticks");
  retyped[4].member = &realization_record::stick_fraction;
  EXPECT_NE(record_layout_id(retyped), id);
  auto moved = table;  // belt_switches (u64) as a member of the record, not of its events
  ASSERT_EQ(std::string(moved[14].name), "belt_switches");
  moved[14].member = &realization_record::realization;
  EXPECT_NE(record_layout_id(moved), id);
  auto swapped = table;
  std::swap(swapped[4], swapped[5]);
  EXPECT_NE(record_layout_id(swapped), id);
  auto shorter = std::span<const record_field>(table).first(table.size() - 1);
  EXPECT_NE(record_layout_id(shorter), id);
}

// The serialized layout's identity (every journal and message carries it)
// is pinned: a change of the statistics schema, the parameter names or the
// record table changes it, on purpose and with a CHANGELOG entry. It covers
// the record table: without its part the id would be the one builds before
// wrote (0x53970b7da65d6768, read from such a journal's header).
TEST(RecordSchema, TheSerializedLayoutIdIsPinnedAndCoversTheRecordTable) {
  EXPECT_EQ(layout_id(), 0x9d33d218398d0c04ULL) << std::hex << "0x" << layout_id();
  EXPECT_NE(layout_id(), 0x53970b7da65d6768ULL);
}

}  // namespace
}  // namespace stickslip
