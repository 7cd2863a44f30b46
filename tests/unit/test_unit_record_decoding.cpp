// A journal record is read back either as exactly the unit that wrote it or
// not at all. The oracle is the encoder itself run on the decoded unit: any
// record the decoder accepts must serialize to the very bytes it was read
// from. A decoder that normalizes a field (fuzz_journal_reader found one: an
// empty accumulator whose mean byte was forged) would accept bytes that no
// unit writes, which a resume then silently replaces.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>

#include "stickslip/error.hpp"
#include "stickslip/serialize.hpp"
#include "stickslip/sweep.hpp"

namespace {

using namespace stickslip;

sweep_spec damped_family_spec() {
  sweep_spec s;  // the fixture of fuzz_journal_reader
  s.base.window = 4.0;
  s.base.damping = 0.3;
  s.base.static_friction = 1.5;
  s.base.kinetic_friction = 1.0;
  s.base.belt_levels = {1.0, -0.5};
  s.base.belt_rates = {1.0, 2.0};
  s.axes = {axis{"k", {4.0, 9.0}}};
  s.realizations = 4;
  s.block_size = 2;
  s.histograms.bins = 5;
  s.keep_records = true;
  s.seed = 7;
  validate(s);
  return s;
}

// The paper model on a window too short for any stick: its stick moments are
// empty accumulators, which have one encoding.
sweep_spec stickless_paper_spec() {
  sweep_spec s;
  s.base.window = 1e-3;
  s.realizations = 2;
  s.block_size = 2;
  s.histograms.bins = 3;
  s.seed = 11;
  validate(s);
  return s;
}

// The paper model with the survival group: its sparse ended/censored counts
// (sweep_spec::statistics, survival_counts) and the grid in the spec.
sweep_spec survival_paper_spec() {
  sweep_spec s;
  s.base.window = 6.0;
  s.base.stiffness = 40.0;
  s.realizations = 3;
  s.block_size = 3;
  s.histograms.bins = 3;
  s.seed = 13;
  s.statistics.survival = true;
  s.survival.bins = 7;
  resolve_survival_grid(s);
  validate(s);
  return s;
}

class UnitRecordDecoding : public ::testing::TestWithParam<sweep_spec (*)()> {};

TEST_P(UnitRecordDecoding, EveryAcceptedSingleByteChangeReadsBackAsWritten) {
  const sweep_spec s = GetParam()();
  const work_unit u = unit_at(s, 0);
  const std::string original = serialize(u, simulate_block(s, u));
  ASSERT_EQ(deserialize_unit_result(original).first, u);
  std::size_t accepted = 0, refused = 0;
  for (std::size_t at = 0; at < original.size(); ++at) {
    for (unsigned mask : {0x01u, 0x80u, 0x91u, 0xffu}) {
      std::string forged = original;
      forged[at] = static_cast<char>(forged[at] ^ mask);
      try {
        const auto [unit, block] = deserialize_unit_result(forged);
        ++accepted;
        ASSERT_EQ(serialize(unit, block), forged) << "byte " << at << " xor " << mask;
      } catch (const error&) {
        ++refused;
      }
    }
  }
  // Both outcomes occur: most bytes are free data (a double, a count), the
  // layout's lengths and flags are checked.
  EXPECT_GT(accepted, original.size());
  EXPECT_GT(refused, 0u);
}

// The journal header: the spec the run was started with.
TEST_P(UnitRecordDecoding, EveryAcceptedSingleByteChangeOfTheHeaderReadsBackAsWritten) {
  const std::string original = serialize(GetParam()());
  std::size_t accepted = 0;
  for (std::size_t at = 0; at < original.size(); ++at) {
    for (unsigned mask : {0x01u, 0x80u, 0x91u, 0xffu}) {
      std::string forged = original;
      forged[at] = static_cast<char>(forged[at] ^ mask);
      try {
        const sweep_spec s = deserialize_sweep_spec(forged);
        ++accepted;
        ASSERT_EQ(serialize(s), forged) << "byte " << at << " xor " << mask;
      } catch (const error&) {
      }
    }
  }
  EXPECT_GT(accepted, 0u);
}

INSTANTIATE_TEST_SUITE_P(Units, UnitRecordDecoding,
                         ::testing::Values(&damped_family_spec, &stickless_paper_spec,
                                           &survival_paper_spec));


// The journal's record layout, written out here by hand (not from the record
// table the codec iterates): the realization, x0, x0', the belt start as a
// signed byte, S_T and S_L as 32 bits, R, the first stick's start and
// duration, its censoring flag as a byte, W_f, W_c, the two causal-score
// moments, the four event counts, the sum of switch times, then the count
// of drawn values. 138 bytes, little-endian: the bytes resumes of earlier
// journals read.
TEST(JournalRecordLayout, IsTheHandWrittenLayoutByteForByte) {
  sweep_spec s = damped_family_spec();
  const work_unit u = unit_at(s, 0);
  block_result r = simulate_block(s, u);
  ASSERT_FALSE(r.records.empty());
  realization_record& x = r.records.front();
  x.realization = 0x0102030405060708u;
  x.x0 = 1.25, x.xdot0 = -2.5, x.belt_start = -1;
  x.sticks = 0x0a0b0c0du, x.slips = 0x01020304u, x.stick_fraction = 0.375;
  x.first_stick_start = 0.5, x.first_stick_duration = 0.75, x.first_stick_censored = true;
  x.friction_power = 3.5, x.damping_power = 4.5;
  x.stick_switch_moment = 5.5, x.stick_time_moment = 6.5;
  x.events = {11, 12, 13, 14, 7.5};
  x.drawn_values.clear();
  std::string expected;
  const auto put = [&](auto v) {
    unsigned char b[sizeof v];
    std::memcpy(b, &v, sizeof v);  // the machines are little-endian, as the format
    expected.append(reinterpret_cast<const char*>(b), sizeof v);
  };
  put(x.realization), put(x.x0), put(x.xdot0), put(static_cast<std::int8_t>(-1));
  put(x.sticks), put(x.slips), put(x.stick_fraction), put(x.first_stick_start);
  put(x.first_stick_duration), put(std::uint8_t{1}), put(x.friction_power), put(x.damping_power);
  put(x.stick_switch_moment), put(x.stick_time_moment);
  put(std::uint64_t{11}), put(std::uint64_t{12}), put(std::uint64_t{13}), put(std::uint64_t{14});
  put(7.5), put(std::uint64_t{0});
  ASSERT_EQ(expected.size(), 138u);
  const std::string message = serialize(u, r);
  EXPECT_NE(message.find(expected), std::string::npos);
  // and it reads back as written
  EXPECT_EQ(deserialize_unit_result(message).second.records.front().sticks, x.sticks);
}

}  // namespace
