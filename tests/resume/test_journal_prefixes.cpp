// The journal's merged prefixes (io/journal.hpp, sweep.hpp merged_prefix): a
// point's blocks merged in order, stored as one record, restore the merge
// with the same bits as merging the blocks one by one; a whole run's journal
// keeps at most a segment per point however many units it ran; a damaged prefix is
// reported and its point recomputed, never misread; a run's last checkpoint
// is written when one is due or the run was stopped, and not otherwise.
#include <gtest/gtest.h>

#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>

#include "stickslip/error.hpp"
#include "stickslip/io/journal.hpp"
#include "stickslip/run/journaled_run.hpp"
#include "stickslip/run/runner.hpp"
#include "stickslip/run/stop.hpp"
#include "stickslip/serialize.hpp"

using namespace stickslip;
namespace fs = std::filesystem;

namespace {

sweep_spec many_blocks() {
  sweep_spec s;
  s.axes = {{"lambda", {0.5, 3.8}}};
  s.base.window = 10.0;
  s.realizations = 600;
  s.block_size = 10;
  s.histograms.bins = 8;
  return s;
}

fs::path fresh(const std::string& name) {
  const auto p = fs::temp_directory_path() / ("stickslip-prefix-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(p);
  return p;
}

bytes bits(const point_statistics& s) { return serialize(work_unit{}, block_result{s, {}}); }

std::vector<bytes> merged_in_order(const sweep_spec& s) {
  ordered_merger m(s);
  for (std::uint64_t i = 0; i < unit_count(s); ++i) m.add(unit_at(s, i), simulate_block(s, unit_at(s, i)));
  std::vector<bytes> out;
  for (std::size_t p = 0; p < point_count(s); ++p) out.push_back(bits(m.merged(p)));
  return out;
}

// Runs `s` on `plan` (a copy) with no checkpoint due during the run (a
// 3600 s interval) and a SIGINT once `units` are merged: the run throws, and
// the journal holds what the stop's checkpoint wrote.
void run_stopped_after(const sweep_spec& s, run::run_plan plan, run::runner& r,
                       std::uint64_t units, double checkpoint_seconds = 3600) {
  plan.checkpoint_interval = std::chrono::duration<double>(checkpoint_seconds);
  run::stop_token stop;
  plan.stop = &stop;
  plan.progress = [&](std::uint64_t done, std::uint64_t, double) {
    if (done >= units) stop.request(SIGINT);
  };
  EXPECT_THROW((void)run::run_journaled(s, plan, io::run_metadata{"c", "f", "v", "g", "t"}, r), error);
}

// Changes a byte of a record's payload in its segment, after the reading.
void damage_on_disk(const io::journal_place& at) {
  std::string data;
  {
    std::ifstream in(*at.segment, std::ios::binary);
    data.assign(std::istreambuf_iterator<char>(in), {});
  }
  data[at.offset + at.length / 2] ^= 0x10;
  std::ofstream(*at.segment, std::ios::binary | std::ios::trunc) << data;
}

// A damaged record (prefix or unit) is refused when read back, naming its
// segment, as a journal changed since it was read.
template <class Record>
void expect_read_back_refused(const Record& r) {
  try {
    (void)r.decode();
    ADD_FAILURE() << "a changed segment was read back";
  } catch (const error& e) {
    EXPECT_EQ(e.code(), exit_code::io_failure);
    EXPECT_NE(std::string(e.what()).find("the journal changed since it was read (CRC mismatch)"),
              std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(*r.place.segment), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(JournalPrefixes, RestoredPrefixContinuesWithTheSameBits) {
  const auto s = many_blocks();
  const auto whole = merged_in_order(s);
  for (const std::uint64_t cut : {1u, 7u, 37u, 59u}) {
    ordered_merger first(s);
    for (std::size_t p = 0; p < point_count(s); ++p)
      for (std::uint64_t b = 0; b < cut; ++b) first.add({p, b}, simulate_block(s, {p, b}));
    ordered_merger second(s);
    for (std::size_t p = 0; p < point_count(s); ++p) {
      const auto rec = serialize_merged_prefix(p, first.merged_blocks(p), first.merged(p));
      auto prefix = deserialize_merged_prefix(rec);
      check_prefix_shape(s, prefix);
      second.restore(std::move(prefix));
    }
    for (std::size_t p = 0; p < point_count(s); ++p)
      for (std::uint64_t b = cut; b < blocks_per_point(s); ++b) second.add({p, b}, simulate_block(s, {p, b}));
    ASSERT_TRUE(second.complete());
    for (std::size_t p = 0; p < point_count(s); ++p)
      EXPECT_EQ(bits(second.merged(p)), whole[p]) << "cut after " << cut << " blocks, point " << p;
  }
}

TEST(JournalPrefixes, AWholeRunKeepsItsPrefixesInFewSegments) {
  const auto s = many_blocks();
  const auto dir = fresh("one-segment");
  run::run_plan plan;
  plan.dir = dir.string();
  plan.checkpoint_interval = std::chrono::duration<double>(0);  // a checkpoint after every unit
  run::thread_runner runner(2);
  const auto out = run::run_journaled(s, plan, io::run_metadata{"cmd", "cfg", "v", "g", "t"}, runner);
  ASSERT_TRUE(out.results);
  EXPECT_EQ(out.computed_units, unit_count(s));
  std::size_t segment_files = 0;
  for (const auto& e : fs::directory_iterator(dir / io::journal_directory))
    segment_files += e.path().filename().string().starts_with("seg-");
  // Superseded segments are removed: what stays is at most one segment per
  // point (the one with its longest prefix), after 120 checkpoints.
  EXPECT_LE(segment_files, point_count(s));
  const auto j = io::read_journal(dir.string(), &s);
  EXPECT_EQ(j.damaged, 0u);
  EXPECT_TRUE(j.units.empty());
  ASSERT_EQ(j.prefixes.size(), point_count(s));
  const auto whole = merged_in_order(s);
  for (const auto& [p, prefix] : j.prefixes) {
    EXPECT_EQ(prefix.blocks, blocks_per_point(s));
    EXPECT_EQ(bits(prefix.decode().stats), whole[p]);
  }
  // A resume with everything journaled computes nothing and gives the same bits.
  plan.resume = true;
  const auto again = run::run_journaled(s, plan, io::run_metadata{}, runner);
  EXPECT_EQ(again.computed_units, 0u);
  EXPECT_EQ(again.resumed_units, unit_count(s));
  for (std::size_t p = 0; p < point_count(s); ++p)
    EXPECT_EQ(bits(again.results->points[p].stats), whole[p]);
  fs::remove_all(dir);
}

TEST(JournalPrefixes, ADamagedPrefixIsReportedAndItsPointRecomputed) {
  const auto s = many_blocks();
  const auto dir = fresh("damaged");
  run::run_plan plan;
  plan.dir = dir.string();
  run::thread_runner runner(1);
  // One segment with every point's whole prefix: the stop's checkpoint
  // after the last unit.
  run_stopped_after(s, plan, runner, unit_count(s));
  fs::path seg;
  for (const auto& e : fs::directory_iterator(dir / io::journal_directory))
    if (e.path().filename().string().starts_with("seg-")) seg = e.path();
  ASSERT_FALSE(seg.empty());
  std::string data;
  {
    std::ifstream in(seg, std::ios::binary);
    data.assign(std::istreambuf_iterator<char>(in), {});
  }
  data[data.size() - 100] ^= 0x10;  // inside the last record (a prefix)
  std::ofstream(seg, std::ios::binary | std::ios::trunc) << data;
  std::vector<std::string> notes;
  const auto j = io::read_journal(dir.string(), &s, [&](const std::string& n) { notes.push_back(n); });
  EXPECT_GE(j.damaged, 1u);
  EXPECT_FALSE(notes.empty());
  EXPECT_LT(j.prefixes.size(), point_count(s));
  plan.resume = true;
  const auto again = run::run_journaled(s, plan, io::run_metadata{}, runner);
  EXPECT_GT(again.computed_units, 0u);
  const auto whole = merged_in_order(s);
  for (std::size_t p = 0; p < point_count(s); ++p)
    EXPECT_EQ(bits(again.results->points[p].stats), whole[p]);
  fs::remove_all(dir);
}

// A journaled prefix is held as where its bytes are (segment, offset,
// length, CRC), not as the bytes: a resume of a large grid holds every
// journaled point until its window. Read back, the bytes are the record's,
// checked again: a segment changed after the reading throws io_failure
// naming it, never a misread point; two prefixes of one length in two
// segments are still compared by their bytes.
TEST(JournalPrefixes, APrefixIsReadBackFromItsSegmentAndCheckedAgain) {
  const auto s = many_blocks();
  const auto dir = fresh("read-back");
  run::run_plan plan;
  plan.dir = dir.string();
  run::thread_runner runner(1);
  run_stopped_after(s, plan, runner, unit_count(s));
  const auto j = io::read_journal(dir.string(), &s);
  ASSERT_EQ(j.prefixes.size(), point_count(s));
  const auto whole = merged_in_order(s);
  const io::journaled_prefix& first = j.prefixes.begin()->second;
  ASSERT_TRUE(first.place.segment);
  EXPECT_EQ(first.bytes().size(), first.place.length);
  for (const auto& [p, prefix] : j.prefixes) EXPECT_EQ(bits(prefix.decode().stats), whole[p]);
  // The same segment under a second name: every prefix twice, of one
  // length, equal bytes: taken once, nothing reported.
  const fs::path seg = *first.place.segment;
  fs::copy_file(seg, seg.parent_path() / (seg.filename().string() + ".bin"));
  std::vector<std::string> notes;
  const auto twice = io::read_journal(dir.string(), &s, [&](const std::string& n) { notes.push_back(n); });
  EXPECT_TRUE(notes.empty()) << notes.front();
  EXPECT_EQ(twice.prefixes.size(), point_count(s));
  fs::remove(seg.parent_path() / (seg.filename().string() + ".bin"));
  // A byte of the first prefix's payload changed after the reading.
  damage_on_disk(first.place);
  expect_read_back_refused(first);
  fs::remove(seg);
  EXPECT_THROW((void)first.bytes(), error);  // gone: "cannot open"
  fs::remove_all(dir);
}

// A journaled unit (a shard's, or a sweep's that keeps records) is held as
// where it is too, and read back and checked again when its window merges
// it: `merge` of the 100,000-point grid's two shards held 577 MB of decoded
// units before.
TEST(JournalPrefixes, AUnitIsReadBackFromItsSegmentAndCheckedAgain) {
  auto s = many_blocks();
  s.keep_records = true;  // every unit journaled as it is
  const auto dir = fresh("unit-read-back");
  run::run_plan plan;
  plan.dir = dir.string();
  run::thread_runner runner(1);
  run_stopped_after(s, plan, runner, unit_count(s), 0.0);  // a segment after every unit
  const auto j = io::read_journal(dir.string(), &s);
  EXPECT_TRUE(j.prefixes.empty());
  ASSERT_EQ(j.units.size(), unit_count(s));
  ASSERT_GT(j.segments, 16u);
  // One reader, in an order that leaves the 8 segments it keeps open at
  // every step (the two points' blocks alternately, from both ends): every
  // unit read back is the one simulated.
  std::vector<work_unit> order;
  const std::uint64_t nb = blocks_per_point(s);
  for (std::uint64_t b = 0; b < nb; ++b)
    for (std::size_t p = 0; p < point_count(s); ++p) order.push_back({p, p == 0 ? b : nb - 1 - b});
  io::journal_readback from;
  for (const auto& u : order) {
    const block_result b = j.units.at(u).decode(from);
    const block_result again = simulate_block(s, u);
    EXPECT_EQ(bits(b.stats), bits(again.stats)) << u.point << " " << u.block;
    EXPECT_EQ(b.records.size(), again.records.size());
  }
  // A segment cut short after the reading: its unit fails, and the same
  // reader goes on reading the others.
  const io::journaled_unit& cut = j.units.at(order[1]);
  fs::resize_file(*cut.place.segment, cut.place.offset + cut.place.length / 2);
  EXPECT_THROW((void)cut.decode(from), error);
  EXPECT_EQ(bits(j.units.at(order[2]).decode(from).stats), bits(simulate_block(s, order[2]).stats));
  EXPECT_EQ(bits(j.units.at(order[0]).decode(from).stats), bits(simulate_block(s, order[0]).stats));
  const io::journaled_unit& first = j.units.begin()->second;
  ASSERT_TRUE(first.place.segment);
  damage_on_disk(first.place);
  expect_read_back_refused(first);
  fs::remove_all(dir);
}

namespace {
std::size_t segment_count(const fs::path& dir) {
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir / io::journal_directory))
    n += e.path().filename().string().starts_with("seg-");
  return n;
}
}  // namespace

// The end of a run follows the checkpoint rule (journal_writer::due): a run
// shorter than its interval writes no segment (its outputs are written next;
// a failure there loses at most the interval's units), one stopped by a
// signal writes its finished units whatever the interval.
TEST(JournalPrefixes, TheLastCheckpointIsWrittenWhenDueOrStopped) {
  const auto s = many_blocks();
  run::thread_runner runner(2);
  {
    const auto dir = fresh("not-due");
    run::run_plan plan;
    plan.dir = dir.string();
    plan.checkpoint_interval = std::chrono::duration<double>(3600);
    plan.outputs_follow = true;  // as sweep_into, which writes the outputs next
    const auto out = run::run_journaled(s, plan, io::run_metadata{"c", "f", "v", "g", "t"}, runner);
    ASSERT_TRUE(out.results);
    EXPECT_EQ(out.computed_units, unit_count(s));
    EXPECT_EQ(segment_count(dir), 0u) << "a checkpoint that was not due";
    const auto whole = merged_in_order(s);
    for (std::size_t p = 0; p < point_count(s); ++p)
      EXPECT_EQ(bits(out.results->points[p].stats), whole[p]);
    fs::remove_all(dir);
  }
  {
    const auto dir = fresh("stopped");
    run::run_plan plan;
    plan.dir = dir.string();
    run_stopped_after(s, plan, runner, 30);
    EXPECT_GE(segment_count(dir), 1u) << "a stopped run kept nothing";
    const auto j = io::read_journal(dir.string(), &s);
    std::uint64_t kept = 0;
    for (const auto& [p, prefix] : j.prefixes) kept += prefix.blocks;
    EXPECT_GE(kept + j.units.size(), 30u);
    plan.resume = true;
    const auto again = run::run_journaled(s, plan, io::run_metadata{}, runner);
    EXPECT_EQ(again.resumed_units, kept + j.units.size());
    EXPECT_EQ(again.resumed_units + again.computed_units, unit_count(s));
    const auto whole = merged_in_order(s);
    for (std::size_t p = 0; p < point_count(s); ++p)
      EXPECT_EQ(bits(again.results->points[p].stats), whole[p]);
    fs::remove_all(dir);
  }
}
