# The full-study benchmark and its floor, included by
# bench/CMakeLists.txt. floor.cpp is compiled once per Highway target and
# dispatched at run time like the core's lane engine (src/core/CMakeLists.txt),
# so that its Log runs at the engine's vector width with FMA.
find_package(hwy CONFIG REQUIRED)
add_executable(stickslip_bench_study bench_study.cpp floor.cpp)
target_link_libraries(stickslip_bench_study PRIVATE stickslip::core hwy::hwy stickslip_warnings)
target_include_directories(stickslip_bench_study PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
target_compile_options(stickslip_bench_study PRIVATE -ffp-contract=off)
