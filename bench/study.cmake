# The full-study benchmark and its floor (issue 6), included by
# bench/CMakeLists.txt. floor.cpp needs AVX2 + FMA so that Highway's static
# target vectorizes Log four doubles wide.
find_package(hwy CONFIG REQUIRED)
add_executable(stickslip_bench_study bench_study.cpp floor.cpp)
target_link_libraries(stickslip_bench_study PRIVATE stickslip::core hwy::hwy stickslip_warnings)
set_source_files_properties(floor.cpp PROPERTIES COMPILE_OPTIONS "-mavx2;-mfma")
