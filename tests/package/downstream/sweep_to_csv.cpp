// Uses stickslip::io on top of stickslip::core: the sweep of core_only.cpp,
// written as summary.csv and summary.json into the directory argv[1] with the
// library's writers. The same sweep run by the `stickslip` binary must give
// the same summary.csv.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include <stickslip/io/metadata.hpp>
#include <stickslip/io/writers.hpp>
#include <stickslip/sweep.hpp>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: sweep_to_csv DIR\n");
    return 2;
  }
  try {
    stickslip::sweep_spec spec;
    spec.axes = {{"lambda", {1.0, 3.8}}};
    spec.realizations = 100;
    spec.seed = 7;
    stickslip::validate(spec);
    const stickslip::result_set rs = stickslip::run_sweep(spec, 1);
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    const auto meta = stickslip::io::make_metadata(argc, argv, "");
    stickslip::io::write_summary_csv(rs, (dir / stickslip::io::summary_csv_file).string());
    stickslip::io::write_summary_json(rs, meta, (dir / stickslip::io::summary_json_file).string());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sweep_to_csv: %s\n", e.what());
    return 1;
  }
}
