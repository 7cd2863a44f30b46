# The full-study benchmark and its floor (issue 6), included by
# bench/CMakeLists.txt. floor.cpp is compiled with the SIMD flags of the core's
# kernels (src/core/CMakeLists.txt: Highway's AVX3 target where the machine has
# AVX-512, else its AVX2 target, i.e. AVX2 + FMA + BMI2 + F16C ...), so that
# its Log runs at the engine's vector width with FMA: with only -mavx2 -mfma
# Highway falls back to its 2-wide SSSE3/SSE4 target.
find_package(hwy CONFIG REQUIRED)
add_executable(stickslip_bench_study bench_study.cpp floor.cpp)
target_link_libraries(stickslip_bench_study PRIVATE stickslip::core hwy::hwy stickslip_warnings)
set_source_files_properties(floor.cpp PROPERTIES COMPILE_OPTIONS "${STICKSLIP_SIMD_FLAGS}")
