// A large grid's outputs streamed window by window (io/streamed_outputs.hpp,
// run::sweep_into): the same files as the whole result set written at once
// (write_all): summary.csv byte for byte, summary.json but for the run's
// elapsed time, results.nc variable by variable (names, dimensions, every
// attribute, every value, bit for bit) and its global attributes; chunks
// that end at the slabs' bounds; nothing left behind by a stop, and a
// resume that finishes the same files.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <netcdf>
#include <sstream>
#include <string>
#include <vector>

#include "stickslip/error.hpp"
#include "stickslip/io/streamed_outputs.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/run/journaled_run.hpp"
#include "stickslip/run/merge.hpp"
#include "stickslip/run/result_memory.hpp"
#include "stickslip/run/runner.hpp"
#include "stickslip/run/stop.hpp"
#include "stickslip/statistics_groups.hpp"
#include "output/writers_detail.hpp"

using namespace stickslip;
namespace fs = std::filesystem;
namespace nc = netCDF;

namespace {

fs::path fresh(const std::string& name) {
  const auto p =
      fs::temp_directory_path() / ("stickslip-stream-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(p);
  return p;
}

// 40 lambda x 2 mu: with a window of 2 points (one row) a streamed run
// widens it to 16 rows (streamed_window_points): slabs of 16, 16 and 8 rows.
sweep_spec grid(const std::string& statistics) {
  sweep_spec s;
  std::vector<double> lambda(40);
  for (std::size_t i = 0; i < lambda.size(); ++i) lambda[i] = 0.2 + 0.25 * static_cast<double>(i);
  s.axes = {{"lambda", lambda}, {"mu", {0.5, 4.0}}};
  s.base.window = 8.0;
  s.realizations = 20;
  s.block_size = 10;
  s.histograms.bins = 60;  // 4,800 values a histogram variable: chunked (>= 4,096)
  s.seed = 5;
  s.statistics = parse_statistics_selection("statistics", statistics);
  if (s.statistics.survival) {
    s.survival.bins = 10;
    s.survival.stick_duration_max = 3.0;
    s.survival.slip_duration_max = 3.0;
  }
  apply_statistics_selection(s);
  return s;
}

const io::run_metadata meta{"stickslip sweep ...", "cfg", "v", "g", "2026-11-29T00:00:00Z"};

run::run_outcome sweep_into(const sweep_spec& s, const fs::path& dir, std::size_t window,
                            const run::stop_token* stop = nullptr,
                            std::function<void(std::uint64_t)> progress = {}) {
  run::run_plan plan;
  plan.dir = dir.string();
  plan.window_points = window;
  plan.stop = stop;
  plan.resume = fs::exists(dir / ".journal");
  if (progress)
    plan.progress = [progress](std::uint64_t done, std::uint64_t, double) { progress(done); };
  run::thread_runner runner(2);
  return run::sweep_into(s, plan, meta, runner);
}

std::string text_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// An attribute's type, length and bytes, as text (netCDF's C API: raw bytes).
std::string attribute_text(const nc::NcAtt& a, int ncid, int varid) {
  std::vector<char> bytes(a.getAttLength() * a.getType().getSize());
  if (!bytes.empty()) {
    EXPECT_EQ(nc_get_att(ncid, varid, a.getName().c_str(), bytes.data()), NC_NOERR);
  }
  std::string hex;
  for (const unsigned char c : bytes) hex += fmt::format("{:02x}", c);
  return fmt::format("{}[{}]={}", a.getType().getName(), a.getAttLength(), hex);
}

// Every variable of a NetCDF file: dimensions, attributes and values (bytes),
// and its chunk extent in the first dimension (0: contiguous); the global
// attributes but `skip`.
struct file_text {
  std::map<std::string, std::string> variables, globals;
  std::map<std::string, std::size_t> first_chunk;
};

file_text read_netcdf(const fs::path& path, const std::string& skip) {
  file_text out;
  nc::NcFile f(path.string(), nc::NcFile::read);
  for (const auto& [name, v] : f.getVars()) {
    std::string text;
    std::size_t values = 1;
    for (const auto& d : v.getDims()) {
      text += fmt::format("{}:{} ", d.getName(), d.getSize());
      values *= d.getSize();
    }
    for (const auto& [att, a] : v.getAtts())
      text += fmt::format("{}={} ", att, attribute_text(a, f.getId(), v.getId()));
    std::vector<char> bytes(values * v.getType().getSize());
    EXPECT_EQ(nc_get_var(f.getId(), v.getId(), bytes.data()), NC_NOERR) << name;
    std::string hex;
    for (const unsigned char c : bytes) hex += fmt::format("{:02x}", c);
    out.variables[name] = text + hex;
    nc::NcVar::ChunkMode mode{};
    std::vector<std::size_t> sizes;
    v.getChunkingParameters(mode, sizes);
    out.first_chunk[name] = mode == nc::NcVar::nc_CHUNKED && !sizes.empty() ? sizes[0] : 0;
  }
  for (const auto& [att, a] : f.getAtts())
    if (att != skip) out.globals[att] = attribute_text(a, f.getId(), NC_GLOBAL);
  return out;
}

// summary.json without its "elapsed_seconds" line.
std::string without_elapsed(const std::string& json) {
  std::istringstream in(json);
  std::string out, line;
  while (std::getline(in, line))
    if (line.find("\"elapsed_seconds\":") == std::string::npos) out += line + '\n';
  return out;
}

void expect_same_outputs(const fs::path& streamed, const fs::path& whole) {
  EXPECT_EQ(text_of(streamed / "summary.csv"), text_of(whole / "summary.csv"));
  EXPECT_EQ(without_elapsed(text_of(streamed / "summary.json")),
            without_elapsed(text_of(whole / "summary.json")));
  const auto a = read_netcdf(streamed / "results.nc", "elapsed_seconds");
  const auto b = read_netcdf(whole / "results.nc", "elapsed_seconds");
  EXPECT_EQ(a.globals, b.globals);
  ASSERT_EQ(a.variables.size(), b.variables.size());
  for (const auto& [name, text] : b.variables) {
    ASSERT_TRUE(a.variables.count(name)) << name << " missing from the streamed results.nc";
    EXPECT_EQ(a.variables.at(name), text) << name;
  }
}

// What a directory holds, but the lock and the journal.
std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) {
    const auto n = e.path().filename().string();
    if (n != ".stickslip.lock" && n != ".journal") names.push_back(n);
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

// Grids whose whole-grid facts differ between rows: mu_s as the first axis
// from mu_k = 4 up (mu defines the model only in its first row, mu_s = 4), a swept belt level v2 (the belt differs
// between points), a 1-axis grid (a row is a point) and a 3-axis grid;
// with chunks of 3 rows (a chunk's rows then divide a slab's: 2 of 16).
TEST(StreamedOutputs, AreTheFilesOfTheWholeResultSetWhereRowsDiffer) {
  std::vector<double> forty(40);
  for (std::size_t i = 0; i < forty.size(); ++i) forty[i] = 4.0 + 0.1 * static_cast<double>(i);
  auto mu_s = grid("paper");
  mu_s.axes = {{"mu_s", forty}, {"lambda", {0.5, 3.8}}};
  mu_s.base.kinetic_friction = 4.0;
  auto belt = grid("paper");
  belt.base.belt_levels = {1.0, -1.0};
  std::vector<double> v2(40);
  for (std::size_t i = 0; i < v2.size(); ++i) v2[i] = -0.2 - 0.02 * static_cast<double>(i);
  belt.axes = {{"v2", v2}, {"mu", {0.5, 4.0}}};
  auto one_axis = grid("paper");
  one_axis.axes = {{"lambda", forty}};
  auto three_axes = grid("paper");
  three_axes.axes.push_back({"k", {4.0, 40.0}});
  const auto saved = io::detail::netcdf_chunk_values;
  int n = 0;
  for (const auto& s : {mu_s, belt, one_axis, three_axes}) {
    ++n;
    const auto streamed = fresh("rows" + std::to_string(n)), whole = fresh("rows-whole" + std::to_string(n));
    const std::size_t row = point_count(s) / s.axes.front().values.size();
    io::detail::netcdf_chunk_values = n == 1 ? 3 * row * 60 : saved;
    ASSERT_TRUE(sweep_into(s, streamed, row).results) << n;
    ASSERT_TRUE(sweep_into(s, whole, 0).results) << n;
    expect_same_outputs(streamed, whole);
    for (const auto& [name, rows] : read_netcdf(streamed / "results.nc", "").first_chunk)
      if (rows != 0) {
        EXPECT_EQ(16 % rows, 0u) << n << " " << name << ": chunks of " << rows << " rows";
      }
    fs::remove_all(streamed);
    fs::remove_all(whole);
  }
  io::detail::netcdf_chunk_values = saved;
}

// A commit that fails (summary.csv cannot be renamed into place: a
// directory of that name) leaves no output and no temporary, keeps the
// journal and says to resume; the resume writes the files.
TEST(StreamedOutputs, AFailedCommitLeavesNothingButTheJournal) {
  const auto s = grid("paper");
  const auto dir = fresh("commit"), whole = fresh("commit-whole");
  fs::create_directories(dir / "summary.csv" / "x");
  run::run_plan plan;
  plan.dir = dir.string();
  plan.window_points = 2;
  plan.overwrite = true;
  run::thread_runner runner(2);
  try {
    (void)run::sweep_into(s, plan, meta, runner);
    ADD_FAILURE() << "the commit did not fail";
  } catch (const error& e) {
    EXPECT_EQ(e.code(), exit_code::io_failure);
    EXPECT_NE(std::string(e.what()).find("rerun with --resume"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::exists(dir / ".journal"));
  EXPECT_EQ(files_in(dir), std::vector<std::string>{"summary.csv"}) << "outputs or temporaries left";
  fs::remove_all(dir / "summary.csv");
  plan.resume = true;
  (void)run::sweep_into(s, plan, meta, runner);
  (void)sweep_into(s, whole, 0);
  expect_same_outputs(dir, whole);
  fs::remove_all(dir);
  fs::remove_all(whole);
}

TEST(StreamedOutputs, AreTheFilesOfTheWholeResultSet) {
  // The paper's selection; the family's with survival curves (fixed grids)
  // and observe times: histograms, joint histograms, level statistics,
  // survival, observed and convergence variables, in slabs.
  for (const std::string selection : {"paper", "paper,family,survival"}) {
    auto s = grid(selection);
    if (selection != "paper") s.observe_times = {1.0, 4.5, 8.0};
    run::thread_runner runner(2);
    run::run_plan plan;
    plan.window_points = 2;
    ASSERT_TRUE(io::streams_outputs(s)) << selection;
    ASSERT_TRUE(run::streams_outputs(s, plan, runner)) << selection;
    EXPECT_EQ(run::sweep_memory_window(s, plan, runner), 32u) << selection;
    const auto streamed = fresh("streamed"), whole = fresh("whole");
    const auto out = sweep_into(s, streamed, 2);
    ASSERT_TRUE(out.results);
    EXPECT_TRUE(out.results->points.empty()) << "a streamed run keeps no point";
    const auto reference = sweep_into(s, whole, 0);
    ASSERT_EQ(reference.results->points.size(), point_count(s));
    expect_same_outputs(streamed, whole);
    EXPECT_EQ(files_in(streamed),
              (std::vector<std::string>{"results.nc", "summary.csv", "summary.json"}));
    // Every chunk within one slab of 16 rows (the last slab: 8).
    std::size_t chunked = 0;
    for (const auto& [name, rows] : read_netcdf(streamed / "results.nc", "").first_chunk) {
      if (rows == 0) continue;
      ++chunked;
      EXPECT_EQ(16 % rows, 0u) << name << ": chunks of " << rows << " rows";
    }
    EXPECT_GT(chunked, 0u) << selection;
    fs::remove_all(streamed);
    fs::remove_all(whole);
  }
}

// Stopped in its second slab, a streamed run leaves no output and no
// temporary beside its journal; resumed, it writes the same files.
TEST(StreamedOutputs, AStoppedRunLeavesNothingAndItsResumeWritesTheSameFiles) {
  const auto s = grid("paper");
  const auto streamed = fresh("stopped"), whole = fresh("stopped-whole");
  run::stop_token stop;
  // 80 points x 2 blocks: the first slab is units 0..63.
  EXPECT_THROW((void)sweep_into(s, streamed, 2, &stop,
                                [&](std::uint64_t done) {
                                  if (done >= 80) stop.request(SIGINT);
                                }),
               error);
  EXPECT_TRUE(fs::exists(streamed / ".journal"));
  EXPECT_EQ(files_in(streamed), std::vector<std::string>{}) << "outputs or temporaries left";
  const auto resumed = sweep_into(s, streamed, 2);
  EXPECT_GE(resumed.resumed_units, 80u);
  (void)sweep_into(s, whole, 0);
  expect_same_outputs(streamed, whole);
  fs::remove_all(streamed);
  fs::remove_all(whole);
}

// What streams: not the derived estimates, a precision target or raw
// records (their columns, trace lengths and files depend on every point),
// not a shard, not a grid within one window.
TEST(StreamedOutputs, StreamOnlyWhatTheWritersCanWriteSlabBySlab) {
  run::thread_runner runner(2);
  run::run_plan plan;
  plan.window_points = 2;
  EXPECT_FALSE(io::streams_outputs(grid("paper,derivatives")));
  auto target = grid("paper");
  target.target_statistic = "R";
  target.target_halfwidth = 0.01;
  EXPECT_FALSE(io::streams_outputs(target));
  auto records = grid("paper");
  records.keep_records = true;
  EXPECT_FALSE(io::streams_outputs(records));
  const auto s = grid("paper");
  auto shard = plan;
  shard.slice = run::parse_shard("1/2");
  EXPECT_FALSE(run::streams_outputs(s, shard, runner));
  auto wide = plan;
  wide.window_points = 100;  // the whole grid in one window
  EXPECT_FALSE(run::streams_outputs(s, wide, runner));
  EXPECT_EQ(run::sweep_memory_window(s, wide, runner), 0u);
}

// The stream refuses slabs out of grid order and a commit before the last
// point, and leaves nothing behind then.
TEST(StreamedOutputs, RefusesSlabsOutOfOrderAndAnEarlyCommit) {
  const auto s = grid("paper");
  const auto dir = fresh("order");
  run::thread_runner runner(2);
  run::run_plan plan;
  plan.dir = dir.string();
  plan.window_points = 0;
  const auto out = run::run_journaled(s, plan, meta, runner);
  ASSERT_TRUE(out.results);
  // Rows 16..39 and 0..15 of the grid as slabs (2 points a row).
  result_set late = *out.results, early = *out.results;
  late.points.erase(late.points.begin(), late.points.begin() + 32);
  early.points.resize(32);
  const auto out_dir = fresh("order-out");
  {
    result_set header;
    header.spec = s;
    io::streamed_outputs stream(header, out_dir.string(), {});
    EXPECT_THROW(stream.slab(late, meta), error);
  }
  EXPECT_FALSE(fs::exists(out_dir / "results.nc.tmp"));
  {
    result_set header;
    header.spec = s;
    io::streamed_outputs stream(header, out_dir.string(), {});
    stream.slab(early, meta);
    EXPECT_EQ(stream.points(), 32u);
    EXPECT_THROW((void)stream.commit(1.0, meta), error);
  }
  EXPECT_FALSE(fs::exists(out_dir)) << "the directory the stream created stays";
  fs::remove_all(dir);
}

// `merge` of shards streams as a sweep does: the same files as the merge
// written whole.
TEST(StreamedOutputs, AMergeOfShardsStreamsTheSameFiles) {
  const auto s = grid("paper");
  std::vector<std::string> dirs;
  for (std::uint32_t i = 0; i < 2; ++i) {
    const auto dir = fresh("shard" + std::to_string(i));
    dirs.push_back(dir.string());
    run::run_plan plan;
    plan.dir = dir.string();
    plan.window_points = 2;
    plan.slice = run::shard{i, 2};
    run::thread_runner runner(2);
    EXPECT_FALSE(run::run_journaled(s, plan, meta, runner).results);
  }
  const auto streamed = fresh("merged"), whole = fresh("merged-whole");
  std::optional<io::streamed_outputs> out;
  std::size_t slabs = 0;
  const auto merged = run::merge_shards(dirs, {}, 2, [&](const result_set& slab,
                                                         const io::run_metadata& m) {
    if (!out) out.emplace(result_set{s, {}, {}}, streamed.string(), io::output_options{});
    out->slab(slab, m);
    ++slabs;
  });
  EXPECT_TRUE(merged.results.points.empty());
  EXPECT_EQ(slabs, 3u);  // 16, 16 and 8 rows
  ASSERT_TRUE(out);
  (void)out->commit(merged.results.elapsed_seconds, merged.metadata);
  const auto at_once = run::merge_shards(dirs, {}, 0);
  (void)io::write_all(at_once.results, at_once.metadata, whole.string());
  expect_same_outputs(streamed, whole);
  for (const auto& d : dirs) fs::remove_all(d);
  fs::remove_all(streamed);
  fs::remove_all(whole);
}
