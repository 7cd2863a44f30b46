// A journal record is read back either as exactly the unit that wrote it or
// not at all. The oracle is the encoder itself run on the decoded unit: any
// record the decoder accepts must serialize to the very bytes it was read
// from. A decoder that normalizes a field (fuzz_journal_reader found one: an
// empty accumulator whose mean byte was forged) would accept bytes that no
// unit writes, which a resume then silently replaces.
#include <gtest/gtest.h>

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

}  // namespace
