// Serialization is exact and never crashes on bad bytes; the journal keeps
// every committed unit, and every kind of damage is reported and skipped.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "stickslip/error.hpp"
#include "stickslip/io/journal.hpp"
#include "stickslip/serialize.hpp"
#include "stickslip/statistics_groups.hpp"

using namespace stickslip;
namespace fs = std::filesystem;

namespace {

sweep_spec small_spec(bool records = true) {
  sweep_spec s;
  s.axes = {{"lambda", {0.3, 4.0}}};
  s.base.window = 10.0;
  s.realizations = 25;
  s.block_size = 10;
  s.histograms.bins = 8;
  s.keep_records = records;
  return s;
}

struct temp_dir {
  fs::path path;
  temp_dir() {
    path = fs::temp_directory_path() /
           ("stickslip-journal-test-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(path);
  }
  ~temp_dir() { fs::remove_all(path); }
};

std::vector<fs::path> segments(const fs::path& dir) {
  std::vector<fs::path> out;
  for (auto& e : fs::directory_iterator(dir / io::journal_directory))
    if (e.path().filename().string().starts_with("seg-")) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

void rewrite(const fs::path& p, const std::function<void(std::string&)>& edit) {
  std::string data;
  {
    std::ifstream in(p, std::ios::binary);
    data.assign(std::istreambuf_iterator<char>(in), {});
  }
  edit(data);
  std::ofstream(p, std::ios::binary | std::ios::trunc) << data;
}

// Writes every unit of `s` into a journal in `dir`, one segment per unit.
void journal_everything(const sweep_spec& s, const fs::path& dir) {
  io::journal_writer w(dir.string(), s, io::run_metadata{"cmd", "cfg", "v", "g", "t"}, "test",
                       std::chrono::seconds(0));
  for (std::uint64_t i = 0; i < unit_count(s); ++i) {
    const auto u = unit_at(s, i);
    w.add(u, simulate_block(s, u));
  }
}

// Bit-exact equality of two statistics (point_statistics has no operator==
// while event_counts lacks one): compare their exact encodings.
bool same_bits(const point_statistics& a, const point_statistics& b) {
  return serialize(work_unit{}, block_result{a, {}}) == serialize(work_unit{}, block_result{b, {}});
}

}  // namespace

TEST(Serialize, BlockResultRoundTripIsExact) {
  const auto s = small_spec();
  const work_unit u{1, 2};
  const auto b = simulate_block(s, u);
  const auto bytes = serialize(u, b);
  const auto [u2, b2] = deserialize_unit_result(bytes);
  EXPECT_EQ(u2, u);
  EXPECT_TRUE(same_bits(b2.stats, b.stats));
  ASSERT_EQ(b2.records.size(), b.records.size());
  EXPECT_EQ(serialize(u2, b2), bytes);
  EXPECT_NO_THROW(check_block_shape(s, u2, b2));
}

// The family's statistics (three belt levels, damping, mu_s > mu_k): every
// accumulator (the generator's scores too), compared by value (operator==, not by re-encoding), and the
// records' powers.
TEST(Serialize, FamilyStatisticsRoundTripByValue) {
  sweep_spec s;
  s.base.damping = 0.4;
  s.base.static_friction = 6.0;
  s.base.kinetic_friction = 4.0;
  s.base.belt_levels = {1.0, -0.5, 0.0};
  s.base.belt_generator = {-2, 1, 1, 0.5, -1, 0.5, 1, 1, -2};
  s.base.window = 10.0;
  s.realizations = 40;
  s.block_size = 20;
  s.keep_records = true;
  const work_unit u{0, 1};
  const auto b = simulate_block(s, u);
  ASSERT_EQ(b.stats.level_fraction.size(), 3u);
  ASSERT_GT(b.stats.stick_duration_onset.total(), 0u);
  ASSERT_GT(b.stats.damping_power.count(), 0u);
  ASSERT_EQ(b.stats.stick_fraction_generator_score.size(), 9u);  // the generator's scores
  ASSERT_EQ(b.stats.stick_fraction_generator_score[1].count(), 20u);
  ASSERT_EQ(b.stats.generator, s.base.belt_generator);
  const auto [u2, b2] = deserialize_unit_result(serialize(u, b));
  EXPECT_TRUE(b2.stats == b.stats);
  ASSERT_EQ(b2.records.size(), b.records.size());
  for (std::size_t i = 0; i < b.records.size(); ++i) {
    EXPECT_EQ(b2.records[i].friction_power, b.records[i].friction_power);
    EXPECT_EQ(b2.records[i].damping_power, b.records[i].damping_power);
  }
  // A merge of the two blocks equals filling both (exact: counts and Chan's merge).
  auto merged = simulate_block(s, {0, 0}).stats;
  merged += b2.stats;
  auto refilled = simulate_block(s, {0, 0}).stats;
  refilled += b.stats;
  EXPECT_TRUE(merged == refilled);
  EXPECT_EQ(merged.stick_duration_onset.total(),
            merged.stick_duration.count());  // one (D, X) per stick
}

// The joint (D, X) histograms exist only with the family statistics: the
// paper's selection allocates none (0 cells, encoded as such), which round
// trips, merges (also into a default-constructed accumulator), and is a
// shape check away from a unit that has one.
TEST(Serialize, JointHistogramsOnlyWithTheFamilyStatistics) {
  sweep_spec paper = small_spec(false);
  paper.statistics = parse_statistics_selection("statistics", "paper");
  apply_statistics_selection(paper);
  ASSERT_FALSE(paper.family_statistics);
  sweep_spec family = small_spec(false);
  family.statistics = parse_statistics_selection("statistics", "paper,family");
  apply_statistics_selection(family);
  ASSERT_TRUE(family.family_statistics);
  const work_unit u{1, 0};
  const auto p = simulate_block(paper, u);
  const auto f = simulate_block(family, u);
  EXPECT_TRUE(p.stats.stick_duration_onset.cells().empty());
  EXPECT_EQ(f.stats.stick_duration_onset.cells().size(), 10u * 10u);  // (8 bins + 2)^2
  EXPECT_EQ(f.stats.stick_duration_onset.total(), f.stats.stick_duration.count());
  for (const auto* b : {&p, &f}) {
    const auto [u2, b2] = deserialize_unit_result(serialize(u, *b));
    EXPECT_TRUE(b2.stats == b->stats);
  }
  EXPECT_NO_THROW(check_block_shape(paper, u, p));
  EXPECT_NO_THROW(check_block_shape(family, u, f));
  // A unit with the other shape is foreign: refused by name.
  try {
    check_block_shape(family, u, p);
    ADD_FAILURE() << "a unit without the joint histogram passed as the family's";
  } catch (const error& e) {
    EXPECT_NE(std::string(e.what()).find("stick_duration_onset: 0 cells, the point has 100"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(check_block_shape(paper, u, f), error);
  // Merges: empty + empty stays empty; a default accumulator takes the cells.
  auto two = p.stats;
  two += simulate_block(paper, {1, 1}).stats;
  EXPECT_TRUE(two.stick_duration_onset.cells().empty());
  point_statistics fresh;
  fresh += f.stats;
  EXPECT_EQ(fresh.stick_duration_onset.cells(), f.stats.stick_duration_onset.cells());
}

TEST(Serialize, ConvergenceTraceAndEmptyAccumulatorsSurvive) {
  const auto s = small_spec(false);
  ordered_merger m(s);
  run_units(s, 1, m);
  block_result merged{m.points()[0], {}};
  ASSERT_FALSE(merged.stats.convergence.empty());
  const auto [u, b] = deserialize_unit_result(serialize(work_unit{0, 0}, merged));
  EXPECT_TRUE(same_bits(b.stats, merged.stats));
  block_result empty{point_statistics(point_parameters(s, 0), s.histograms), {}};
  EXPECT_TRUE(same_bits(deserialize_unit_result(serialize(work_unit{0, 0}, empty)).second.stats, empty.stats));
}

TEST(Serialize, SpecRoundTripAndDifferences) {
  auto s = small_spec();
  EXPECT_TRUE(same_results(deserialize_sweep_spec(serialize(s)), s));
  EXPECT_EQ(deserialize_sweep_spec(serialize(s)), s);
  auto t = s;
  t.realizations = 26;
  EXPECT_EQ(first_difference(s, t), "realizations: 25 vs 26");
  t = s;
  t.axes[0].values[1] = 4.5;
  EXPECT_NE(first_difference(s, t).find("lambda value #2"), std::string::npos);
  t = s;
  t.engine = sweep_engine::reference;  // speed only: same results
  EXPECT_TRUE(same_results(s, t));
  EXPECT_EQ(fingerprint(s), fingerprint(t));
}

TEST(Serialize, EveryTruncationThrowsCleanly) {
  const auto s = small_spec();
  const auto bytes = serialize(work_unit{0, 1}, simulate_block(s, work_unit{0, 1}));
  for (std::size_t n = 0; n < bytes.size(); ++n)
    EXPECT_THROW((void)deserialize_unit_result(std::string_view(bytes).substr(0, n)), error) << n;
  const auto spec_bytes = serialize(s);
  for (std::size_t n = 0; n < spec_bytes.size(); ++n)
    EXPECT_THROW((void)deserialize_sweep_spec(std::string_view(spec_bytes).substr(0, n)), error);
}

TEST(Serialize, RandomCorruptionNeverCrashes) {
  const auto s = small_spec();
  const auto bytes = serialize(work_unit{0, 1}, simulate_block(s, work_unit{0, 1}));
  std::mt19937_64 rng(7);
  int thrown = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    auto bad = bytes;
    for (int k = 0; k < 1 + trial % 4; ++k)
      bad[rng() % bad.size()] = static_cast<char>(rng());
    try {
      auto [u, b] = deserialize_unit_result(bad);
      check_block_shape(s, u, b);
    } catch (const error&) {
      ++thrown;
    }
  }
  EXPECT_GT(thrown, 0);
}

TEST(Journal, ReadsBackEveryCommittedUnit) {
  temp_dir d;
  const auto s = small_spec();
  journal_everything(s, d.path);
  std::vector<std::string> problems;
  const auto j = io::read_journal(d.path.string(), &s, [&](const std::string& m) { problems.push_back(m); });
  EXPECT_TRUE(problems.empty());
  ASSERT_EQ(j.units.size(), unit_count(s));
  ASSERT_TRUE(j.metadata);
  EXPECT_EQ(j.metadata->created_utc, "t");
  for (const auto& [u, b] : j.units) EXPECT_TRUE(same_bits(b.decode().stats, simulate_block(s, u).stats));
}

TEST(Journal, ChangedConfigurationIsRefused) {
  temp_dir d;
  const auto s = small_spec();
  journal_everything(s, d.path);
  auto t = s;
  t.seed = 2;
  try {
    (void)io::read_journal(d.path.string(), &t);
    FAIL() << "no error";
  } catch (const error& e) {
    EXPECT_EQ(e.code(), exit_code::resume_mismatch);
    EXPECT_NE(std::string(e.what()).find("seed: 1 vs 2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(io::journal_writer(d.path.string(), t, {}, "x"), error);
  t = s;
  t.engine = sweep_engine::reference;
  EXPECT_EQ(io::read_journal(d.path.string(), &t).units.size(), unit_count(s));
}

TEST(Journal, CorruptOrTruncatedSegmentsAreReportedAndSkipped) {
  temp_dir d;
  const auto s = small_spec();
  journal_everything(s, d.path);
  auto segs = segments(d.path);
  ASSERT_EQ(segs.size(), unit_count(s));
  rewrite(segs[0], [](std::string& x) { x[x.size() - 5] ^= 0x40; });       // CRC mismatch
  rewrite(segs[1], [](std::string& x) { x.resize(x.size() / 2); });        // truncated
  rewrite(segs[2], [](std::string& x) { x.clear(); });                     // empty
  rewrite(segs[3], [](std::string& x) { x[2] = 'X'; });                    // bad magic
  std::ofstream(d.path / io::journal_directory / ".tmp-seg-half-written.bin") << "garbage";
  std::vector<std::string> problems;
  const auto j = io::read_journal(d.path.string(), &s, [&](const std::string& m) { problems.push_back(m); });
  EXPECT_EQ(problems.size(), 4u);
  EXPECT_EQ(j.damaged, 4u);
  EXPECT_EQ(j.units.size(), unit_count(s) - 4);
  for (const auto& [u, b] : j.units) EXPECT_TRUE(same_bits(b.decode().stats, simulate_block(s, u).stats));
}

// A record journaled twice (two writers, or a rewritten checkpoint): the
// same bytes are one record, silently; different bytes for one unit, or for
// one point's prefix of one length, are damage: reported and dropped (the
// point then falls back on its unit records, and what none covers is
// recomputed). Units with records (keep_records) and without; prefixes
// (whole runs without records); and every statistics group with observe
// times, since a unit read twice is compared by re-encoding the first (the
// codec must be canonical for all of them).
TEST(Journal, ARecordReadTwiceIsKeptOnceAndAConflictIsRecomputed) {
  sweep_spec everything = small_spec(false);
  everything.statistics = {true, true, true, true, {}};
  everything.family_statistics = true;
  everything.survival.stick_duration_max = everything.survival.slip_duration_max = 5.0;
  everything.observe_times = {2.0, 7.0};
  for (const auto& s : {small_spec(true), small_spec(false), everything}) {
    const bool records = s.keep_records;
    temp_dir d;
    journal_everything(s, d.path);
    const work_unit same = unit_at(s, 0), changed = unit_at(s, 1);
    const std::size_t point = 1;  // its prefix is journaled twice, then changed
    const auto blocks = blocks_per_point(s);
    ordered_merger whole(s);
    run_units(s, 1, whole);
    const point_statistics merged = whole.points()[point];
    {
      io::journal_writer w(d.path.string(), s, io::run_metadata{"cmd", "cfg", "v", "g", "t"},
                           "again", std::chrono::seconds(0));
      w.add(same, simulate_block(s, same));  // the same bytes again
      block_result other = simulate_block(s, changed);
      other.stats.expected_switches += 1.0;  // the same unit, other bytes
      w.add(changed, other);
      if (!records) {  // a sweep that keeps records journals no prefixes
        w.add_prefix(point, blocks, merged);
        w.add_prefix(point, blocks, merged);  // the same prefix twice
      }
      w.flush();
    }
    std::vector<std::string> problems;
    auto j = io::read_journal(d.path.string(), &s, [&](const std::string& m) { problems.push_back(m); });
    ASSERT_EQ(problems.size(), 1u) << (problems.empty() ? "" : problems[0]);
    EXPECT_NE(problems[0].find("journaled twice with different contents"), std::string::npos)
        << problems[0];
    EXPECT_EQ(j.units.count(same), 1u);
    EXPECT_EQ(j.units.count(changed), 0u);  // recomputed
    EXPECT_TRUE(same_bits(j.units.at(same).decode().stats, simulate_block(s, same).stats));
    if (records) continue;
    ASSERT_EQ(j.prefixes.count(point), 1u);
    EXPECT_TRUE(same_bits(j.prefixes.at(point).decode().stats, merged));
    // A prefix of the same length with other bytes: the point is recomputed.
    {
      io::journal_writer w(d.path.string(), s, io::run_metadata{"cmd", "cfg", "v", "g", "t"},
                           "conflict", std::chrono::seconds(0));
      point_statistics other = merged;
      other.expected_switches += 1.0;
      w.add_prefix(point, blocks, other);
      w.flush();
    }
    problems.clear();
    j = io::read_journal(d.path.string(), &s, [&](const std::string& m) { problems.push_back(m); });
    ASSERT_EQ(problems.size(), 2u);  // segments are read in name order: either may come first
    EXPECT_TRUE(problems[0].find("two journaled merges of its first") != std::string::npos ||
                problems[1].find("two journaled merges of its first") != std::string::npos)
        << problems[0] << "\n" << problems[1];
    EXPECT_EQ(j.prefixes.count(point), 0u);
    for (std::uint64_t b = 0; b < blocks; ++b)  // its units are what a resume merges
      EXPECT_EQ(j.units.count(work_unit{point, b}), 1u) << "block " << b;
  }
}

TEST(Journal, DamagedHeaderStillChecksRecordsAgainstTheCurrentSpec) {
  temp_dir d;
  const auto s = small_spec();
  journal_everything(s, d.path);
  rewrite(d.path / io::journal_directory / "header.bin", [](std::string& x) { x.resize(7); });
  std::vector<std::string> problems;
  auto j = io::read_journal(d.path.string(), &s, [&](const std::string& m) { problems.push_back(m); });
  EXPECT_EQ(problems.size(), 1u);
  EXPECT_EQ(j.units.size(), unit_count(s));
  auto t = s;
  t.realizations = 30;  // another config: its fingerprint differs, so no record is used
  problems.clear();
  j = io::read_journal(d.path.string(), &t, [&](const std::string& m) { problems.push_back(m); });
  EXPECT_TRUE(j.units.empty());
  // and a writer repairs the header
  { io::journal_writer w(d.path.string(), s, {}, "repair"); }
  problems.clear();
  j = io::read_journal(d.path.string(), &s, [&](const std::string& m) { problems.push_back(m); });
  EXPECT_TRUE(problems.empty());
}

TEST(Journal, UnwritableDirectoryIsAClearError) {
  try {
    io::journal_writer w("/proc/stickslip-cannot-exist", small_spec(), {}, "x");
    FAIL();
  } catch (const error& e) {
    EXPECT_EQ(e.code(), exit_code::io_failure);
  }
}

// Format version 2 put the layout id (statistics and parameters) into every message header
// (after the 4-byte tag and the 4-byte version): data from another version or
// another list of statistics is refused by name, never misread.
TEST(Serialize, AnotherFormatVersionOrStatisticsSchemaIsRefusedByName) {
  const auto s = small_spec();
  const auto bytes = serialize(work_unit{0, 1}, simulate_block(s, work_unit{0, 1}));
  auto expect_refused = [](const std::string& data, const std::string& what) {
    try {
      (void)deserialize_unit_result(data);
      FAIL() << "no error for " << what;
    } catch (const error& e) {
      EXPECT_EQ(e.code(), exit_code::io_failure);
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  auto v1 = bytes;
  v1[4] = 1;  // little-endian u32 version
  expect_refused(v1, "format version 1 (this program reads version " + std::to_string(serial_format_version) + ")");
  auto other_schema = bytes;
  other_schema[8] ^= 0x01;  // first byte of the u64 layout id
  expect_refused(other_schema, "another list of statistics, model parameters or record fields");
}

TEST(Journal, AJournalOfFormatVersion1IsReportedAndRecomputed) {
  temp_dir d;
  const auto s = small_spec();
  journal_everything(s, d.path);
  // What stickslip 0.1.0 wrote: the same frames with version 1.
  rewrite(d.path / io::journal_directory / "header.bin", [](std::string& x) { x[4] = 1; });
  for (const auto& seg : segments(d.path)) rewrite(seg, [](std::string& x) { x[4] = 1; });
  std::vector<std::string> problems;
  const auto j = io::read_journal(d.path.string(), &s, [&](const std::string& m) { problems.push_back(m); });
  EXPECT_TRUE(j.units.empty());
  ASSERT_FALSE(problems.empty());
  for (const auto& p : problems)
    EXPECT_NE(p.find("format version 1 (this program reads " + std::to_string(serial_format_version) + ")"), std::string::npos) << p;
}

// One process journaling the same directory twice within a second (a Python
// sweep interrupted, then resumed at once): the second writer's segments must
// not replace the first one's (they were named by time, pid and a sequence
// number that restarts with every writer).
TEST(Journal, TwoWritersOfOneProcessKeepEachOthersSegments) {
  temp_dir d;
  const auto s = small_spec();
  const io::run_metadata meta{"cmd", "cfg", "v", "g", "t"};
  const auto n = unit_count(s);
  ASSERT_GE(n, 2u);
  for (std::uint64_t i = 0; i < 2; ++i) {
    io::journal_writer w(d.path.string(), s, meta, "run", std::chrono::seconds(0));
    w.add(unit_at(s, i), simulate_block(s, unit_at(s, i)));
  }
  const auto j = io::read_journal(d.path.string(), &s);
  EXPECT_EQ(j.units.size(), 2u);
}
