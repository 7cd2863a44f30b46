// Shared by the writer tests: one small sweep (2 x 3 grid) run once, and a
// fresh temporary directory per test.
#pragma once
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "stickslip/io/metadata.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::testing {

inline sweep_spec small_grid_spec() {
  sweep_spec s;
  s.base.window = 10.0;
  s.axes = {{"lambda", {0.5, 2.0}}, {"mu", {0.5, 1.0, 3.0}}};
  s.realizations = 200;
  s.block_size = 50;
  s.seed = 7;
  s.histograms.bins = 20;
  // Every group but survival, so that the writers' tests see every variable (the family
  // statistics are on: the spec's default engine setting).
  s.statistics = parse_statistics_selection("statistics", "paper,family,derivatives");
  return s;
}

inline io::run_metadata small_metadata() {
  const char* argv[] = {"stickslip", "sweep", "--lambda", "0.5,2", "--mu", "0.5,1,3",
                        "--seed",    "7"};
  return io::make_metadata(8, argv, "# resolved configuration\nseed = 7\nrealizations = 200\n");
}

inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A unique empty directory, removed with everything in it at destruction.
class temp_dir {
 public:
  temp_dir() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "stickslip-test-XXXXXX").string();
    if (!::mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed");
    path_ = tmpl;
  }
  temp_dir(const temp_dir&) = delete;
  temp_dir& operator=(const temp_dir&) = delete;
  ~temp_dir() {
    std::error_code ec;
    std::filesystem::permissions(path_, std::filesystem::perms::owner_all,
                                 std::filesystem::perm_options::add, ec);
    std::filesystem::remove_all(path_, ec);
  }
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  [[nodiscard]] std::string operator/(const std::string& name) const {
    return (path_ / name).string();
  }

 private:
  std::filesystem::path path_;
};

class writers_test : public ::testing::Test {
 protected:
  static const result_set& rs() {
    static const result_set r = run_sweep(small_grid_spec(), 2);
    return r;
  }
  temp_dir dir_;
};

}  // namespace stickslip::testing
