# tumble_micro, the per-call micro-benchmarks (Google Benchmark), and tumble_floor_check.
# Included by benchmarks/CMakeLists.txt, in its scope, after peers/peers.cmake (whose
# TUMBLE_BENCH_HAVE_PINOCCHIO/MUJOCO add the peers' sources, peers/*_micro.cpp).

find_package(benchmark QUIET)
if(benchmark_FOUND)
  add_executable(
    tumble_micro
    micro/micro.cpp
    micro/params_euler_parameters.cpp
    micro/params_rodrigues.cpp
    micro/params_rotation_vector.cpp
    micro/params_tait_bryan.cpp
    micro/params_proper_euler.cpp
    micro/baselines.cpp
    micro/jacobian.cpp
    micro/chain.cpp)
  target_link_libraries(tumble_micro PRIVATE tumble::tumble tumble_project_options
                        benchmark::benchmark)
  # Sources include each other by their path under benchmarks/ ("micro/common.hpp").
  target_include_directories(tumble_micro PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  if(TUMBLE_BENCH_HAVE_PINOCCHIO)
    target_sources(tumble_micro PRIVATE peers/pinocchio_micro.cpp)
    target_link_libraries(tumble_micro PRIVATE tumble_bench_pinocchio)
    target_compile_definitions(tumble_micro PRIVATE TUMBLE_BENCH_HAVE_PINOCCHIO)
  endif()
  if(TUMBLE_BENCH_HAVE_MUJOCO)
    target_sources(tumble_micro PRIVATE peers/mujoco_micro.cpp)
    target_link_libraries(tumble_micro PRIVATE tumble_bench_mujoco)
    target_compile_definitions(tumble_micro PRIVATE TUMBLE_BENCH_HAVE_MUJOCO)
  endif()
  if(TUMBLE_BENCH_NATIVE)
    target_compile_options(tumble_micro PRIVATE -march=native)
  endif()
  # Recorded in the JSON context, so a result says how it was built.
  string(TOUPPER "${CMAKE_BUILD_TYPE}" _tumble_bt)
  set(_tumble_flags "${CMAKE_CXX_FLAGS} ${CMAKE_CXX_FLAGS_${_tumble_bt}}")
  if(TUMBLE_BENCH_NATIVE)
    string(APPEND _tumble_flags " -march=native")
  endif()
  string(STRIP "${_tumble_flags}" _tumble_flags)
  target_compile_definitions(tumble_micro PRIVATE "TUMBLE_BENCH_FLAGS=\"${_tumble_flags}\"")

  # tumble_floor_check: the floor ratio (tumble qddot / hand-written, Euler parameters, centroid)
  # timed a second way, a std::chrono loop with both in one translation unit.
  add_executable(tumble_floor_check micro/floor_check.cpp)
  target_link_libraries(tumble_floor_check PRIVATE tumble::tumble tumble_project_options
                        benchmark::benchmark)
  target_include_directories(tumble_floor_check PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  if(TUMBLE_BENCH_NATIVE)
    target_compile_options(tumble_floor_check PRIVATE -march=native)
  endif()
else()
  message(STATUS "tumble benchmarks: Google Benchmark not found, tumble_micro is skipped")
endif()
