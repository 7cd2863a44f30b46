// The writers against a real small sweep: results.nc read back with the
// netCDF library, summary.json / summary.csv / records.csv checked value by
// value, and write_all's all-or-nothing behaviour on failure.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <netcdf>

#include "stickslip/error.hpp"
#include "stickslip/uncertainty/parameter_law.hpp"
#include "output/writers_detail.hpp"
#include "writers_fixture.hpp"

namespace stickslip::testing {
namespace {

namespace fs = std::filesystem;
namespace nc = netCDF;

std::string text_att(const nc::NcVar& v, const std::string& name) {
  std::string s;
  v.getAtt(name).getValues(s);
  return s;
}
std::string text_att(const nc::NcFile& f, const std::string& name) {
  std::string s;
  f.getAtt(name).getValues(s);
  return s;
}
std::vector<double> doubles(const nc::NcVar& v) {
  std::size_t n = 1;
  for (const auto& d : v.getDims()) n *= d.getSize();
  std::vector<double> out(n);
  v.getVar(out.data());
  return out;
}
std::vector<long long> int64s(const nc::NcVar& v) {
  std::size_t n = 1;
  for (const auto& d : v.getDims()) n *= d.getSize();
  std::vector<long long> out(n);
  v.getVar(out.data());
  return out;
}
// Equal as stored: the same double, or both NaN.
void expect_same(double expected, double actual, const std::string& what) {
  if (std::isnan(expected))
    EXPECT_TRUE(std::isnan(actual)) << what;
  else
    EXPECT_EQ(expected, actual) << what;
}
std::size_t count_lines(const std::string& s) {
  return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n'));
}
bool have_program(const char* name) {
  return std::system(fmt::format("command -v {} >/dev/null 2>&1", name).c_str()) == 0;
}

using writers = writers_test;

TEST_F(writers, NetcdfHasOneDimensionPerAxisWithCoordinatesAndUnits) {
  const auto path = dir_ / "results.nc";
  io::write_netcdf(rs(), small_metadata(), path);
  nc::NcFile f(path, nc::NcFile::read);
  ASSERT_EQ(f.getDim("lambda").getSize(), 2u);
  ASSERT_EQ(f.getDim("mu").getSize(), 3u);
  EXPECT_EQ(f.getDim("bin").getSize(), 20u);
  EXPECT_EQ(f.getDim("trace").getSize(), 4u);  // 200 realizations in blocks of 50
  EXPECT_TRUE(f.getDim("point").isNull());
  EXPECT_EQ(doubles(f.getVar("lambda")), (std::vector<double>{0.5, 2.0}));
  EXPECT_EQ(doubles(f.getVar("mu")), (std::vector<double>{0.5, 1.0, 3.0}));
  EXPECT_EQ(text_att(f.getVar("lambda"), "units"), "1/s");
  EXPECT_EQ(text_att(f.getVar("mu"), "units"), "1");
  EXPECT_FALSE(text_att(f.getVar("lambda"), "long_name").empty());
  // Axis order is the spec's: (lambda, mu).
  const auto dims = f.getVar("stick_fraction_mean").getDims();
  ASSERT_EQ(dims.size(), 2u);
  EXPECT_EQ(dims[0].getName(), "lambda");
  EXPECT_EQ(dims[1].getName(), "mu");
  for (const char* v : {"stick_fraction_mean", "stick_duration_std", "slip_duration_ci95_low",
                        "first_stick_duration_ci95_high", "sticks_per_time_mean",
                        "slips_per_time_mean", "band_half_width", "max_stick_duration",
                        "stick_duration_density", "stick_duration_bin_low",
                        "convergence_R_mean", "convergence_stick_duration_ci95_half_width"}) {
    const auto var = f.getVar(v);
    ASSERT_FALSE(var.isNull()) << v;
    EXPECT_FALSE(text_att(var, "units").empty()) << v;
    EXPECT_FALSE(text_att(var, "long_name").empty()) << v;
  }
  EXPECT_EQ(text_att(f.getVar("stick_duration_mean"), "units"), "s");
  EXPECT_EQ(text_att(f.getVar("sticks_per_time_mean"), "units"), "1/s");
}

// The model family's statistics: names, dimensions, units and long
// names written from docs/outputs.md, values equal to the result set.
TEST_F(writers, NetcdfHasTheFamilyStatisticsWithDimensionsAndUnits) {
  const auto path = dir_ / "results.nc";
  io::write_netcdf(rs(), small_metadata(), path);
  nc::NcFile f(path, nc::NcFile::read);
  const std::size_t points = rs().points.size(), bins = rs().spec.histograms.bins;
  EXPECT_EQ(f.getDim("belt_level").getSize(), 2u);
  EXPECT_EQ(f.getDim("bin_y").getSize(), bins);
  const struct {
    const char* name;
    const char* units;
  } vars[] = {{"stick_onset_position_mean", "m"}, {"stick_onset_position_density", "1/m"},
              {"friction_power_mean", "W"},       {"damping_power_mean", "W"},
              {"belt_level_fraction_mean", "1"},  {"belt_level_velocity", "m/s"},
              {"stick_duration_onset_counts", "1"}};
  for (const auto& v : vars) {
    const auto var = f.getVar(v.name);
    ASSERT_FALSE(var.isNull()) << v.name;
    EXPECT_EQ(text_att(var, "units"), v.units) << v.name;
    EXPECT_FALSE(text_att(var, "long_name").empty()) << v.name;
  }
  const auto fraction = doubles(f.getVar("belt_level_fraction_mean"));
  const auto friction = doubles(f.getVar("friction_power_mean"));
  const auto joint = int64s(f.getVar("stick_duration_onset_counts"));
  ASSERT_EQ(fraction.size(), points * 2);
  ASSERT_EQ(joint.size(), points * bins * bins);
  for (std::size_t i = 0; i < points; ++i) {
    const auto& st = rs().points[i].stats;
    EXPECT_EQ(fraction[2 * i], st.level_fraction[0].mean());
    EXPECT_EQ(fraction[2 * i + 1], st.level_fraction[1].mean());
    EXPECT_EQ(friction[i], st.friction_power.mean());
    long long sum = 0;
    for (std::size_t k = 0; k < bins * bins; ++k) sum += joint[i * bins * bins + k];
    EXPECT_EQ(static_cast<std::uint64_t>(sum) + st.stick_duration_onset.outside(),
              st.stick_duration.count());
  }
}

TEST_F(writers, NetcdfStatisticsEqualTheResultSetExactly) {
  const auto path = dir_ / "results.nc";
  io::write_netcdf(rs(), small_metadata(), path);
  nc::NcFile f(path, nc::NcFile::read);
  struct stat_ref {
    const char* name;
    mean_variance point_statistics::*member;
  };
  const stat_ref stats[] = {{"stick_fraction", &point_statistics::stick_fraction},
                            {"sticks_per_time", &point_statistics::sticks_per_time},
                            {"slips_per_time", &point_statistics::slips_per_time},
                            {"stick_duration", &point_statistics::stick_duration},
                            {"first_stick_duration", &point_statistics::first_stick_duration},
                            {"slip_duration", &point_statistics::slip_duration}};
  for (const auto& st : stats) {
    const std::string n = st.name;
    const auto mean = doubles(f.getVar(n + "_mean"));
    const auto sd = doubles(f.getVar(n + "_std"));
    const auto lo = doubles(f.getVar(n + "_ci95_low"));
    const auto hi = doubles(f.getVar(n + "_ci95_high"));
    const auto count = int64s(f.getVar(n + "_count"));
    ASSERT_EQ(mean.size(), rs().points.size());
    for (std::size_t i = 0; i < rs().points.size(); ++i) {
      const auto& mv = rs().points[i].stats.*st.member;
      expect_same(mv.mean(), mean[i], n + "_mean");
      expect_same(mv.std_dev(), sd[i], n + "_std");
      expect_same(mv.mean() - mv.ci95_half_width(), lo[i], n + "_ci95_low");
      expect_same(mv.mean() + mv.ci95_half_width(), hi[i], n + "_ci95_high");
      EXPECT_EQ(static_cast<std::uint64_t>(count[i]), mv.count()) << n;
    }
  }
  const auto realizations = int64s(f.getVar("realizations"));
  const auto no_stick = int64s(f.getVar("no_stick_count"));
  const auto switches = int64s(f.getVar("belt_switches"));
  const auto lambda_at = doubles(f.getVar("switch_rate"));
  const auto density = doubles(f.getVar("stick_duration_density"));
  const auto high = doubles(f.getVar("stick_duration_bin_high"));
  const auto trace_n = int64s(f.getVar("convergence_realizations"));
  const auto trace_R = doubles(f.getVar("convergence_R_mean"));
  for (std::size_t i = 0; i < rs().points.size(); ++i) {
    const auto& p = rs().points[i];
    EXPECT_EQ(realizations[i], 200);
    EXPECT_EQ(static_cast<std::uint64_t>(no_stick[i]), p.stats.no_stick);
    EXPECT_EQ(static_cast<std::uint64_t>(switches[i]), p.stats.events.belt_switches);
    EXPECT_EQ(lambda_at[i], p.parameters.switch_rate);
    for (std::size_t b = 0; b < 20; ++b)
      EXPECT_EQ(density[i * 20 + b], p.stats.stick_duration_hist.density(b));
    EXPECT_EQ(high[i * 20 + 19], p.parameters.max_stick_duration());  // default range [0, d_max]
    ASSERT_EQ(p.stats.convergence.size(), 4u);
    for (std::size_t t = 0; t < 4; ++t) {
      EXPECT_EQ(static_cast<std::uint64_t>(trace_n[i * 4 + t]), p.stats.convergence[t].realizations);
      expect_same(p.stats.convergence[t].R_mean, trace_R[i * 4 + t], "convergence_R_mean");
    }
    expect_same(p.stats.stick_fraction.mean(), trace_R[i * 4 + 3], "last trace entry = mean");
  }
}

TEST_F(writers, NetcdfRowsAreTheSameWrittenWholeBySlabByPointOrByPartRow) {
  const auto read_all = [](const std::string& path) {
    nc::NcFile f(path, nc::NcFile::read);
    return std::make_pair(doubles(f.getVar("slip_duration_density")),
                          doubles(f.getVar("convergence_stick_duration_mean")));
  };
  const auto chunks_of = [](const std::string& path, const std::string& name) {
    nc::NcFile f(path, nc::NcFile::read);
    nc::NcVar::ChunkMode mode{};
    std::vector<std::size_t> sizes;
    f.getVar(name).getChunkingParameters(mode, sizes);
    return mode == nc::NcVar::nc_CHUNKED ? sizes : std::vector<std::size_t>{};
  };
  const auto saved = io::detail::netcdf_chunk_values;
  io::detail::netcdf_chunk_values = 4096;  // (3, 2, 20) bin variables: one chunk each
  io::write_netcdf(rs(), small_metadata(), dir_ / "whole.nc");
  io::detail::netcdf_chunk_values = 60;  // one slab per lambda (2 x 20 values)
  io::write_netcdf(rs(), small_metadata(), dir_ / "slabs.nc");
  io::detail::netcdf_chunk_values = 20;  // every row alone
  io::write_netcdf(rs(), small_metadata(), dir_ / "points.nc");
  io::detail::netcdf_chunk_values = 3;  // a row in 7 chunks
  io::write_netcdf(rs(), small_metadata(), dir_ / "parts.nc");
  io::detail::netcdf_chunk_values = saved;
  const auto whole = read_all(dir_ / "whole.nc");
  EXPECT_EQ(whole.first.size(), 6u * 20u);
  EXPECT_EQ(whole.first[5 * 20 + 7], rs().points[5].stats.slip_duration_hist.density(7));
  EXPECT_EQ(whole, read_all(dir_ / "slabs.nc"));
  EXPECT_EQ(whole, read_all(dir_ / "points.nc"));
  EXPECT_EQ(whole, read_all(dir_ / "parts.nc"));
  // Below 4096 values a variable is contiguous (no chunks to set).
  EXPECT_TRUE(chunks_of(dir_ / "slabs.nc", "slip_duration_density").empty());
}

TEST(netcdf_chunks, AChunkIsARunOfWholeTrailingDimensions) {
  using io::detail::chunk_shape;
  using v = std::vector<std::size_t>;
  EXPECT_EQ(chunk_shape({40, 8, 50}, 1 << 17), (v{40, 8, 50}));  // the paper grid: one chunk
  EXPECT_EQ(chunk_shape({400, 250, 50}, 1 << 17), (v{10, 250, 50}));  // 10 slabs of lambda
  EXPECT_EQ(chunk_shape({400, 250}, 1 << 17), (v{400, 250}));
  EXPECT_EQ(chunk_shape({400, 250, 50, 50}, 1 << 17), (v{1, 52, 50, 50}));
  EXPECT_EQ(chunk_shape({4, 3, 20}, 3), (v{1, 1, 3}));  // part of a row
  EXPECT_EQ(chunk_shape({4, 3, 20}, 20), (v{1, 1, 20}));
  EXPECT_EQ(chunk_shape({4, 3, 20}, 130), (v{2, 3, 20}));
  // The default: a 6,400-point grid's histograms in one chunk, the
  // 100,000-point grid's in 41 slabs of lambda.
  EXPECT_EQ(chunk_shape({80, 80, 50}, io::detail::netcdf_chunk_values), (v{80, 80, 50}));
  EXPECT_EQ(chunk_shape({400, 250, 50}, io::detail::netcdf_chunk_values), (v{41, 250, 50}));
}

// Every write covers whole chunks and the writes tile the grid in order:
// each chunk is compressed once (with netCDF's default chunks, writing a
// 400 x 250 grid's histograms slab by slab did not end in 11 minutes).
TEST(netcdf_chunks, RowRunsTileTheGridInWholeChunks) {
  using io::detail::chunk_shape;
  using io::detail::row_runs;
  const std::vector<std::vector<std::size_t>> shapes = {
      {400, 250, 50}, {40, 8, 50}, {7, 5, 3, 20}, {7, 5, 3, 20, 20}, {1, 9, 20}, {13, 1, 4}};
  for (const auto& shape : shapes)
    for (const std::size_t target : {1, 3, 20, 60, 100, 4096, 1 << 17}) {
      const auto chunk = chunk_shape(shape, target);
      std::size_t values = 1;
      for (auto c : chunk) values *= c;
      EXPECT_LE(values, target);
      const std::size_t grid_rank = shape.size() - 1;  // the last dimension is the row
      const std::vector<std::size_t> grid(shape.begin(), shape.begin() + grid_rank);
      const std::vector<std::size_t> grid_chunk(chunk.begin(), chunk.begin() + grid_rank);
      std::size_t next = 0, points = 1;
      for (auto n : grid) points *= n;
      for (const auto& r : row_runs(grid, grid_chunk)) {
        ASSERT_EQ(r.first, next);
        std::size_t covered = 1;
        for (std::size_t d = 0; d < grid_rank; ++d) {
          covered *= r.count[d];
          // whole chunks: starts on a chunk boundary, and ends on one or at the edge
          EXPECT_EQ(r.start[d] % grid_chunk[d], 0u);
          EXPECT_TRUE(r.count[d] % grid_chunk[d] == 0 || r.start[d] + r.count[d] == grid[d]);
          EXPECT_LE(r.start[d] + r.count[d], grid[d]);
        }
        EXPECT_EQ(covered, r.points);
        EXPECT_LE(r.points, std::max<std::size_t>(1, target / shape.back()));
        next += r.points;
      }
      EXPECT_EQ(next, points);
    }
}

TEST_F(writers, NetcdfGlobalAttributesHoldSeedConfigAndFixedParameters) {
  const auto meta = small_metadata();
  const auto path = dir_ / "results.nc";
  io::write_netcdf(rs(), meta, path);
  nc::NcFile f(path, nc::NcFile::read);
  unsigned long long seed = 0;
  f.getAtt("seed").getValues(&seed);
  EXPECT_EQ(seed, 7u);
  EXPECT_EQ(text_att(f, "resolved_config"), meta.resolved_config);
  EXPECT_EQ(text_att(f, "Conventions"), "CF-1.8");
  EXPECT_EQ(text_att(f, "command_line"), meta.command_line);
  EXPECT_EQ(text_att(f, "version"), meta.version);
  EXPECT_EQ(text_att(f, "git_revision"), meta.git_revision);
  EXPECT_EQ(text_att(f, "created_utc"), meta.created_utc);
  EXPECT_FALSE(text_att(f, "title").empty());
  EXPECT_FALSE(text_att(f, "source").empty());
  double ta = 0;
  f.getAtt("ta").getValues(&ta);
  EXPECT_EQ(ta, 10.0);
  EXPECT_TRUE(f.getAtt("lambda").isNull());  // swept: a coordinate, not an attribute
}

// The one belt of the grid (summary.json's base, results.nc's attributes)
// is given only where every point has it: a swept lambda makes the rates a
// coordinate (summary.json gave the first point's, results.nc the default
// lambda = 1's), a swept V the levels. A user's SciPy check found it.
TEST_F(writers, TheBeltOfTheGridIsGivenOnlyWhereItIsOneForEveryPoint) {
  const auto base_of = [](const std::string& json) {
    const auto at = json.find("\"base\"");
    return json.substr(at, json.find('}', at) - at);
  };
  const auto belt_in = [&](const result_set& r, std::vector<double>& levels,
                           std::vector<double>& generator, std::string& base) {
    const fs::path dir = dir_ / "belt";
    fs::remove_all(dir);
    io::write_all(r, small_metadata(), dir.string());
    nc::NcFile f((dir / "results.nc").string(), nc::NcFile::read);
    const auto read = [&](const char* name, std::vector<double>& out) {
      out.clear();
      const auto att = f.getAtt(name);
      if (att.isNull()) return;
      out.resize(att.getAttLength());
      att.getValues(out.data());
    };
    read("belt_levels", levels);
    read("belt_generator", generator);
    std::ifstream in(dir / "summary.json");
    base = base_of(std::string(std::istreambuf_iterator<char>(in), {}));
  };
  std::vector<double> levels, generator;
  std::string base;
  // lambda swept (0.5, 2): the levels are one, the rates are not.
  belt_in(rs(), levels, generator, base);
  EXPECT_EQ(levels, (std::vector<double>{1.0, -1.0}));
  EXPECT_TRUE(generator.empty());
  EXPECT_NE(base.find("\"belt_levels\": [1, -1]"), std::string::npos) << base;
  EXPECT_NE(base.find("\"belt_generator\": null"), std::string::npos) << base;
  EXPECT_NE(base.find("\"belt_rates\": null"), std::string::npos) << base;
  // One lambda (2.5), V swept (1, 2): the rates are one, the levels are not.
  auto spec = small_grid_spec();
  spec.base.switch_rate = 2.5;
  spec.axes = {{"V", {1.0, 2.0}}};
  spec.realizations = 20;
  spec.block_size = 20;
  belt_in(run_sweep(spec, 1), levels, generator, base);
  EXPECT_TRUE(levels.empty());
  EXPECT_EQ(generator, (std::vector<double>{-2.5, 2.5, 2.5, -2.5}));
  EXPECT_NE(base.find("\"belt_levels\": null"), std::string::npos) << base;
  EXPECT_NE(base.find("\"belt_rates\": [2.5, 2.5]"), std::string::npos) << base;
  // Nothing of the belt swept: both, the point's own.
  spec.axes = {{"mu", {1.0, 3.0}}};
  belt_in(run_sweep(spec, 1), levels, generator, base);
  EXPECT_EQ(levels, (std::vector<double>{1.0, -1.0}));
  EXPECT_EQ(generator, (std::vector<double>{-2.5, 2.5, 2.5, -2.5}));
  EXPECT_NE(base.find("\"belt_generator\": [[-2.5, 2.5], [2.5, -2.5]]"), std::string::npos) << base;
  // A law on a level whose median is the default's (v2 = -1): the levels
  // are drawn per realization, so none is the grid's.
  spec.uncertain = {{"v2", parse_law("uniform(-1.5, -0.5)", "v2")}};
  belt_in(run_sweep(spec, 1), levels, generator, base);
  EXPECT_TRUE(levels.empty());
  EXPECT_EQ(generator, (std::vector<double>{-2.5, 2.5, 2.5, -2.5}));
  EXPECT_NE(base.find("\"belt_levels\": null"), std::string::npos) << base;
  // A law on lambda: the rates.
  spec.uncertain = {{"lambda", parse_law("uniform(1, 4)", "lambda")}};
  belt_in(run_sweep(spec, 1), levels, generator, base);
  EXPECT_EQ(levels, (std::vector<double>{1.0, -1.0}));
  EXPECT_TRUE(generator.empty());
  EXPECT_NE(base.find("\"belt_rates\": null"), std::string::npos) << base;
}

TEST_F(writers, NetcdfWithoutAxesHasOnePointDimension) {
  auto spec = small_grid_spec();
  spec.axes.clear();
  spec.realizations = 20;
  spec.block_size = 20;
  const auto one = run_sweep(spec, 1);
  const auto path = dir_ / "results.nc";
  io::write_netcdf(one, small_metadata(), path);
  nc::NcFile f(path, nc::NcFile::read);
  EXPECT_EQ(f.getDim("point").getSize(), 1u);
  EXPECT_EQ(doubles(f.getVar("stick_fraction_mean"))[0], one.points[0].stats.stick_fraction.mean());
  double lambda = 0;
  f.getAtt("lambda").getValues(&lambda);
  EXPECT_EQ(lambda, spec.base.switch_rate);
  // summary.json still carries lambda and mu.
  const auto points = io::summary_json_points(one);
  EXPECT_NE(points.find(fmt::format("\"lambda\": {}, \"mu\": {}", spec.base.switch_rate,
                                    spec.base.friction_coefficient)),
            std::string::npos)
      << points;
}

TEST_F(writers, MissingStatisticsAreNaNInNetcdfAndNullInJson) {
  auto copy = rs();
  copy.points[0].stats.first_stick_duration = mean_variance{};  // as if no point ever stuck
  const auto path = dir_ / "results.nc";
  io::write_netcdf(copy, small_metadata(), path);
  nc::NcFile f(path, nc::NcFile::read);
  EXPECT_TRUE(std::isnan(doubles(f.getVar("first_stick_duration_mean"))[0]));
  EXPECT_EQ(int64s(f.getVar("first_stick_duration_count"))[0], 0);
  const auto points = io::summary_json_points(copy);
  EXPECT_NE(points.find("\"first_stick_duration\": {\"mean\": null, \"std\": null, \"ci95\": "
                        "[null, null]}"),
            std::string::npos);
  EXPECT_EQ(points.find("nan"), std::string::npos);
}

TEST_F(writers, SummaryJsonCarriesEveryStatisticRoundTripExact) {
  const auto meta = small_metadata();
  const auto path = dir_ / "summary.json";
  io::write_summary_json(rs(), meta, path);
  const auto text = read_text(path);
  EXPECT_EQ(text, io::summary_json(rs(), meta));
  EXPECT_NE(text.find(io::summary_json_points(rs())), std::string::npos);
  for (const auto& p : rs().points) {
    // fmt "{}" prints the shortest text that parses back to the same double.
    const auto stat = [](const mean_variance& mv) {
      return fmt::format("{{\"mean\": {}, \"std\": {}, \"ci95\": [{}, {}]}}", mv.mean(),
                         mv.std_dev(), mv.mean() - mv.ci95_half_width(),
                         mv.mean() + mv.ci95_half_width());
    };
    const auto& s = p.stats;
    const auto expected = fmt::format(
        "{{\"lambda\": {}, \"mu\": {}, \"realizations\": 200, \"R\": {}, \"sticks_per_time\": {}, "
        "\"slips_per_time\": {}, \"stick_duration\": {}, \"first_stick_duration\": {}, "
        "\"slip_duration\": {}, \"stick_onset_position\": {}, \"friction_power\": {}, "
        "\"damping_power\": {}, \"belt_level_fraction\": [{}, {}], \"no_stick\": {}",
        p.parameters.switch_rate, p.parameters.friction_coefficient, stat(s.stick_fraction),
        stat(s.sticks_per_time), stat(s.slips_per_time), stat(s.stick_duration),
        stat(s.first_stick_duration), stat(s.slip_duration), stat(s.stick_onset_position),
        stat(s.friction_power), stat(s.damping_power), stat(s.level_fraction.at(0)),
        stat(s.level_fraction.at(1)), s.no_stick);
    EXPECT_NE(text.find(expected), std::string::npos) << expected;
  }
  EXPECT_NE(text.find("\"seed\": 7"), std::string::npos);
  EXPECT_NE(text.find(fmt::format("\"elapsed_seconds\": {}\n}}\n", rs().elapsed_seconds)),
            std::string::npos);
}

TEST_F(writers, SummaryJsonParsesWithPythonAndHasTheDocumentedKeys) {
  if (!have_program("/usr/bin/python3")) GTEST_SKIP() << "/usr/bin/python3 not found";
  const auto path = dir_ / "summary.json";
  io::write_summary_json(rs(), small_metadata(), path);
  const auto script = dir_ / "check.py";
  {
    std::ofstream py(script);
    py << R"(import json, sys
def no_constants(name):
    raise ValueError("non-JSON constant " + name)
doc = json.load(open(sys.argv[1]), parse_constant=no_constants)
assert list(doc.keys()) == ["parameters", "points", "elapsed_seconds"], list(doc.keys())
par = doc["parameters"]
for k in ["base", "axes", "seed", "realizations", "block_size", "histograms", "version",
          "git_revision", "config"]:
    assert k in par, k
assert par["seed"] == 7 and par["realizations"] == 200 and par["block_size"] == 50
assert [a["name"] for a in par["axes"]] == ["lambda", "mu"]
assert par["axes"][1]["values"] == [0.5, 1.0, 3.0]
assert par["histograms"]["bins"] == 20
assert len(doc["points"]) == 6
required = ["lambda", "mu", "realizations", "R", "sticks_per_time", "slips_per_time",
            "stick_duration", "first_stick_duration", "slip_duration"]
for p in doc["points"]:
    assert list(p.keys())[:len(required)] == required, list(p.keys())
    for s in required[3:]:
        assert list(p[s].keys()) == ["mean", "std", "ci95"], p[s]
        assert len(p[s]["ci95"]) == 2
        assert p[s]["ci95"][0] <= p[s]["mean"] <= p[s]["ci95"][1]
assert [(p["lambda"], p["mu"]) for p in doc["points"]] == [
    (0.5, 0.5), (0.5, 1.0), (0.5, 3.0), (2.0, 0.5), (2.0, 1.0), (2.0, 3.0)]
print("ok")
)";
  }
  const auto cmd = fmt::format("/usr/bin/python3 '{}' '{}' > '{}' 2>&1", script, path,
                               dir_ / "python.log");
  const int rc = std::system(cmd.c_str());
  EXPECT_EQ(rc, 0) << read_text(dir_ / "python.log");
}

TEST_F(writers, SummaryJsonPointsAreByteIdenticalForAnyThreadCount) {
  const auto one = run_sweep(small_grid_spec(), 1);
  const auto three = run_sweep(small_grid_spec(), 3);
  EXPECT_EQ(io::summary_json_points(one), io::summary_json_points(three));
  EXPECT_EQ(io::summary_json_points(one), io::summary_json_points(rs()));
  EXPECT_EQ(io::summary_csv(one), io::summary_csv(three));
}

TEST_F(writers, SummaryCsvHasAHeaderAndOneRowPerPoint) {
  const auto path = dir_ / "summary.csv";
  io::write_summary_csv(rs(), path);
  const auto text = read_text(path);
  EXPECT_EQ(count_lines(text), 1 + rs().points.size());
  EXPECT_EQ(text.rfind("lambda,mu,realizations,R_mean,R_std,R_ci95_low,R_ci95_high,", 0), 0u);
  const auto& p = rs().points[4];  // lambda = 2, mu = 1
  EXPECT_NE(text.find(fmt::format("\n2,1,200,{},{},", p.stats.stick_fraction.mean(),
                                  p.stats.stick_fraction.std_dev())),
            std::string::npos);
  const auto header = text.substr(0, text.find('\n'));
  const auto columns = std::count(header.begin(), header.end(), ',');
  std::istringstream rows(text);
  std::string row;
  while (std::getline(rows, row)) EXPECT_EQ(std::count(row.begin(), row.end(), ','), columns);
}

TEST_F(writers, RecordsCsvHasOneRowPerRealizationWhenKept) {
  auto spec = small_grid_spec();
  spec.keep_records = true;
  spec.realizations = 30;
  spec.block_size = 7;
  const auto kept = run_sweep(spec, 2);
  const auto path = dir_ / "records.csv";
  io::write_records_csv(kept, path);
  const auto text = read_text(path);
  EXPECT_EQ(count_lines(text), 1 + 6 * 30u);
  EXPECT_EQ(text.rfind("point,lambda,mu,realization,x0,", 0), 0u);
  EXPECT_THROW(io::write_records_csv(rs(), dir_ / "none.csv"), stickslip::error);
  EXPECT_FALSE(fs::exists(dir_ / "none.csv"));
}

TEST_F(writers, WriteAllCreatesTheDirectoryAndEveryFile) {
  const auto out = dir_ / "a/b/out";
  io::write_all(rs(), small_metadata(), out);
  for (const char* name : {"results.nc", "summary.json", "summary.csv"})
    EXPECT_TRUE(fs::is_regular_file(fs::path(out) / name)) << name;
  EXPECT_FALSE(fs::exists(fs::path(out) / "records.csv"));  // not kept
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(out)) {
    ++files;
    EXPECT_NE(e.path().extension(), ".tmp");
  }
  EXPECT_EQ(files, 3u);
  // Writing again replaces the files in place.
  io::write_all(rs(), small_metadata(), out);
  EXPECT_EQ(read_text(fs::path(out) / "summary.csv"), io::summary_csv(rs()));
}

TEST_F(writers, WriteAllIntoAnUncreatableDirectoryThrowsAndLeavesNothing) {
  { std::ofstream(dir_ / "plain_file") << "not a directory"; }
  const auto out = dir_ / "plain_file/out";
  try {
    io::write_all(rs(), small_metadata(), out);
    FAIL() << "expected an io_error";
  } catch (const stickslip::error& e) {
    EXPECT_EQ(e.code(), exit_code::io_failure);
    EXPECT_NE(std::string(e.what()).find("plain_file/out"), std::string::npos) << e.what();
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_.path()), fs::directory_iterator{}), 1);
}

TEST_F(writers, WriteAllRenamesNothingWhenOneFileFails) {
  const auto out = dir_ / "out";
  fs::create_directories(fs::path(out) / "summary.csv.tmp");  // summary.csv cannot be written
  { std::ofstream(fs::path(out) / "summary.csv.tmp" / "keep") << "x"; }
  try {
    io::write_all(rs(), small_metadata(), out);
    FAIL() << "expected an io_error";
  } catch (const stickslip::error& e) {
    EXPECT_EQ(e.code(), exit_code::io_failure);
    EXPECT_NE(std::string(e.what()).find("summary.csv"), std::string::npos) << e.what();
  }
  // results.nc and summary.json were written first, as temporaries: none of
  // them may remain, renamed or not.
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(out)) left.push_back(e.path().filename().string());
  EXPECT_EQ(left, std::vector<std::string>{"summary.csv.tmp"});
}

TEST_F(writers, WriteAllIntoAReadOnlyDirectoryThrowsAndLeavesNothing) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores directory permissions";
  const auto out = dir_ / "ro";
  fs::create_directory(out);
  fs::permissions(out, fs::perms::owner_read | fs::perms::owner_exec);
  EXPECT_THROW(io::write_all(rs(), small_metadata(), out), stickslip::error);
  EXPECT_TRUE(fs::is_empty(out));
}

TEST_F(writers, SingleWriterFailureKeepsTheOldFile) {
  const auto path = dir_ / "results.nc";
  io::write_netcdf(rs(), small_metadata(), path);
  const auto before = read_text(path);
  auto bad = rs();
  bad.points.pop_back();  // no longer one point per grid point
  EXPECT_THROW(io::write_netcdf(bad, small_metadata(), path), stickslip::error);
  EXPECT_EQ(read_text(path), before);
  EXPECT_FALSE(fs::exists(path + ".tmp"));
}

TEST_F(writers, NcdumpShowsASelfDescribingHeader) {
  if (!have_program("ncdump")) GTEST_SKIP() << "ncdump not found";
  const auto path = dir_ / "results.nc";
  io::write_netcdf(rs(), small_metadata(), path);
  const auto log = dir_ / "header.cdl";
  ASSERT_EQ(std::system(fmt::format("ncdump -h '{}' > '{}' 2>&1", path, log).c_str()), 0);
  const auto cdl = read_text(log);
  for (const char* expected :
       {"lambda = 2 ;", "mu = 3 ;", "bin = 20 ;", "double lambda(lambda) ;",
        "lambda:units = \"1/s\" ;", "double stick_fraction_mean(lambda, mu) ;",
        "stick_fraction_mean:long_name", "stick_fraction_mean:description",
        "double stick_duration_density(lambda, mu, bin) ;",
        "double convergence_R_mean(lambda, mu, trace) ;", ":Conventions = \"CF-1.8\" ;",
        ":seed = 7ULL ;", ":resolved_config = "})
    EXPECT_NE(cdl.find(expected), std::string::npos) << expected << "\n" << cdl;
}

}  // namespace
}  // namespace stickslip::testing

// A rerun without records into a directory that holds an older records.csv
// must not leave that file behind next to results it does not describe.
TEST(write_all, WithoutRecordsRemovesAStaleRecordsFile) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "stickslip_stale_records";
  fs::remove_all(dir);
  stickslip::sweep_spec s;
  s.axes = {{"lambda", {1.0}}};
  s.realizations = 20;
  s.base.window = 5;
  s.keep_records = true;
  const auto meta = stickslip::io::make_metadata(0, nullptr, "");
  stickslip::io::write_all(stickslip::run_sweep(s, 1), meta, dir.string());
  ASSERT_TRUE(fs::exists(dir / "records.csv"));
  s.keep_records = false;
  stickslip::io::write_all(stickslip::run_sweep(s, 1), meta, dir.string());
  EXPECT_TRUE(fs::exists(dir / "summary.json"));
  EXPECT_FALSE(fs::exists(dir / "records.csv"));
  fs::remove_all(dir);
}
