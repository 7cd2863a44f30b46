// What every output says about the run: the MPI ranks and threads
// it ran with, the belt start law by name, and which parameters were swept
// (a swept parameter has no single base value).
#include <gtest/gtest.h>

#include <netcdf>
#include <string>

#include "output/writers_detail.hpp"
#include "writers_fixture.hpp"

namespace stickslip::testing {
namespace {

namespace nc = netCDF;

bool contains(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos;
}

using writers_metadata = writers_test;

TEST_F(writers_metadata, RanksAndThreadsAreWrittenWhereverThreadsAre) {
  auto r = rs();
  r.ranks = 3;
  r.threads = 5;
  const auto json = io::summary_json(r, small_metadata());
  EXPECT_TRUE(contains(json, "\"threads\": 5")) << json;
  EXPECT_TRUE(contains(json, "\"ranks\": 3")) << json;
  const auto path = dir_ / "results.nc";
  io::write_netcdf(r, small_metadata(), path);
  nc::NcFile f(path, nc::NcFile::read);
  int ranks = 0, threads = 0;
  f.getAtt("ranks").getValues(&ranks);
  f.getAtt("threads").getValues(&threads);
  EXPECT_EQ(ranks, 3);
  EXPECT_EQ(threads, 5);
}

TEST_F(writers_metadata, ARunWithoutMpiRecordsOneRank) {
  EXPECT_EQ(rs().ranks, 1u);  // run_sweep: the non-MPI path
  EXPECT_TRUE(contains(io::summary_json(rs(), small_metadata()), "\"ranks\": 1"));
}

TEST_F(writers_metadata, BeltStartLawIsWrittenByName) {
  for (const auto& [law, name] : {std::pair{0, "stationary"}, {1, "+1"}, {-1, "-1"}}) {
    auto r = rs();
    r.spec.initial.belt_start = law;
    const auto json = io::summary_json(r, small_metadata());
    EXPECT_TRUE(contains(json, std::string("\"belt_start\": \"") + name + "\"")) << json;
    const auto path = dir_ / ("results" + std::to_string(law + 1) + ".nc");
    io::write_netcdf(r, small_metadata(), path);
    nc::NcFile f(path, nc::NcFile::read);
    std::string att;
    f.getAtt("initial_belt_start").getValues(att);
    EXPECT_EQ(att, name);
  }
}

TEST_F(writers_metadata, SweptParametersHaveNoBaseValue) {
  // The fixture sweeps lambda and mu; the spec's base still holds lambda = 1, mu = 5.
  const auto json = io::summary_json(rs(), small_metadata());
  EXPECT_TRUE(contains(json, "\"mu\": null")) << json;
  EXPECT_TRUE(contains(json, "\"lambda\": null")) << json;
  EXPECT_TRUE(contains(json, "\"k\": 4,")) << json;
  EXPECT_TRUE(contains(json, "\"swept\": [\"lambda\", \"mu\"]")) << json;
}

}  // namespace
}  // namespace stickslip::testing
