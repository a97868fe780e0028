# tumble_bench, the README's main job: per-call costs, work precision, scaling and ensembles:
#   cmake -S . -B build -DCMAKE_BUILD_TYPE=Release && cmake --build build -j2 --target tumble_bench
#   ./build/benchmarks/tumble_bench            # --full for the complete sweep, --help for options
# Included by benchmarks/CMakeLists.txt, in its scope, so that tumble_bench is built in
# build/benchmarks/: it uses the peers' detection (peers/peers.cmake: TUMBLE_BENCH_HAVE_PINOCCHIO,
# target tumble_bench_pinocchio, MuJoCo's and Exudyn's) and tumble_micro (micro/micro.cmake) when
# they exist.
# Source paths are relative to benchmarks/, one folder per study.
#
# The results (CSV, PNG, summary.txt, the raw micro-benchmark output micro.txt/.json) go to ${PROJECT_BINARY_DIR}/benchmark-results unless
# --out says otherwise. The plots are drawn by main/plot.py with matplotlib; the
# Python that runs it defaults to Debian's /usr/bin/python3 (python3-matplotlib) when present,
# since the python3 first on PATH may lack matplotlib. Set TUMBLE_BENCH_PLOT_PYTHON to change it.

if(NOT TARGET tumble::cvode)
  message(STATUS "tumble benchmarks: SUNDIALS CVODE not found, tumble_bench is skipped")
  return()
endif()

if(EXISTS /usr/bin/python3)
  set(_tumble_plot_python_default /usr/bin/python3)
else()
  set(_tumble_plot_python_default python3)
endif()
set(TUMBLE_BENCH_PLOT_PYTHON "${_tumble_plot_python_default}" CACHE STRING
    "Python (with matplotlib) that tumble_bench runs to draw its plots")

# The driver reads like a table of contents: the problems, the methods (tumble, the floors, the
# peers), the sweep, the report, the CSV writer, each in its own file (see their top comments).
add_executable(tumble_bench
  main/main.cpp        # the phases of the main job, in order
  main/options.cpp     # command-line options
  work_precision/problems.cpp    # problems, exact references, error measures
  work_precision/tumble_a.cpp    # method: tumble, parameterizations of the default run
  work_precision/tumble_b.cpp    # method: tumble, the other Euler sequences (--full)
  work_precision/tumble_c.cpp    # method: tumble, the quasi-velocity state form, CVODE
  work_precision/methods.cpp     # the list of methods (one entry each)
  floors/cvode_rk4.cpp      # methods: hand-written [q; qdot] CVODE floor, fixed-step RK4
  floors/sundials.cpp  # methods: hand-written [p; omega] in CVODE, ARKODE F78
  floors/odeint.cpp    # methods: hand-written [p; omega] in Boost.Odeint
  peers/pinocchio_work_precision.cpp   # method: Pinocchio's aba in CVODE (when installed)
  peers/mujoco_work_precision.cpp      # method: MuJoCo's RK4 (when installed)
  work_precision/sweep.cpp       # which runs to make, and making them
  scaling/scaling.cpp     # the scaling study (chain of N bodies)
  mechanisms/study.cpp    # the mechanisms' study (e): its problems, methods, tolerances
  main/report.cpp      # the terminal tables
  main/csv.cpp         # the CSV files
  main/tools.cpp       # the programs it runs: tumble_micro, the plot script
)
# tumble_test_support (tests/support/CMakeLists.txt): support/torque_free.hpp, the exact solution
# of the torque-free body.
target_link_libraries(tumble_bench PRIVATE tumble::cvode tumble_test_support tumble_project_options)

# The floors' ARKODE (ERKStep, Fehlberg 7(8)) and Boost.Odeint (header-only). SUNDIALS 6 names
# its targets SUNDIALS::arkode_shared/_static, 7 also SUNDIALS::arkode.
set(_tumble_arkode "")
foreach(_cand SUNDIALS::arkode SUNDIALS::arkode_shared SUNDIALS::arkode_static)
  if(TARGET ${_cand})
    set(_tumble_arkode ${_cand})
    break()
  endif()
endforeach()
if(NOT _tumble_arkode)
  find_library(TUMBLE_ARKODE_LIBRARY NAMES sundials_arkode)
  set(_tumble_arkode ${TUMBLE_ARKODE_LIBRARY})
endif()
if(NOT _tumble_arkode)
  message(FATAL_ERROR "tumble_bench: SUNDIALS' ARKODE not found (Debian: libsundials-dev)")
endif()
find_package(Boost 1.65 REQUIRED)  # Boost.Odeint, header-only (Debian: libboost-dev)
target_link_libraries(tumble_bench PRIVATE ${_tumble_arkode} Boost::headers)
# tumble's own explicit integrator (OdeintIntegrator) on tumble's scenes, when the library
# provides it (tumble::odeint: Boost >= 1.74).
if(TARGET tumble::odeint)
  # The mechanisms' study (e) runs the front door and OdeintIntegrator beside CVODE's BDF: one
  # translation unit per problem, each instantiating its scene type (compiler memory).
  target_sources(tumble_bench PRIVATE
    work_precision/tumble_d.cpp   # method: tumble's scenes under OdeintIntegrator
    mechanisms/pendulum.cpp       # mechanism: IFToMM A01, the simple pendulum
    mechanisms/four_bar.cpp       # mechanism: IFToMM A02, the N-four-bar
    mechanisms/andrews.cpp        # mechanism: IFToMM A03, Andrews' squeezing mechanism
    mechanisms/bricard.cpp        # mechanism: IFToMM A04, Bricard's mechanism
    mechanisms/flyball.cpp        # mechanism: IFToMM A05, the stiff flyball governor
    mechanisms/chain.cpp          # mechanism: an open spatial chain of six hinged rods
    peers/pinocchio_mechanisms.cpp  # mechanisms: Pinocchio's aba in Odeint on the chain
    peers/mujoco_mechanisms.cpp   # mechanisms: MuJoCo's RK4 on them (when installed)
    peers/exudyn_mechanisms.cpp)  # mechanisms: Exudyn's solvers on them (when installed)
  target_link_libraries(tumble_bench PRIVATE tumble::odeint)
  target_compile_definitions(tumble_bench PRIVATE TUMBLE_BENCH_HAVE_TUMBLE_ODEINT=1)
else()
  message(STATUS "tumble_bench: without tumble::odeint (OdeintIntegrator's runs are skipped)")
endif()
target_include_directories(tumble_bench PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})

# (d) the ensemble study: Ensemble (oneTBB) with OdeintIntegrator, when both exist; and, when
# tumble::mpi exists, the same runs over MPI processes in a program of their own,
# tumble_bench_mpi, which tumble_bench launches under mpiexec with 1 and 2 processes (the flags
# as for the MPI tests, tests/CMakeLists.txt). ensembles/alloc.cpp replaces the global
# operator new of tumble_bench to count the allocations per run (off except around those runs).
if(TARGET tumble::ensemble AND TARGET tumble::odeint)
  target_sources(tumble_bench PRIVATE
    ensembles/ensemble.cpp   # the ensemble study: threads, serial loops, memory
    ensembles/alloc.cpp)     # operator new counted
  target_link_libraries(tumble_bench PRIVATE tumble::ensemble)
  target_compile_definitions(tumble_bench PRIVATE TUMBLE_BENCH_HAVE_ENSEMBLE=1)
  if(TARGET tumble::mpi)
    add_executable(tumble_bench_mpi ensembles/mpi.cpp)
    target_link_libraries(tumble_bench_mpi PRIVATE tumble::mpi tumble::odeint
                          tumble_project_options)
    target_include_directories(tumble_bench_mpi PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
    if(TUMBLE_BENCH_NATIVE)
      target_compile_options(tumble_bench_mpi PRIVATE -march=native)
    endif()
    add_dependencies(tumble_bench tumble_bench_mpi)
    set(_tumble_bench_mpiexec_flags ${MPIEXEC_PREFLAGS})
    execute_process(COMMAND ${MPIEXEC_EXECUTABLE} --version OUTPUT_VARIABLE _tumble_mpiexec_version
                    ERROR_QUIET)
    if(_tumble_mpiexec_version MATCHES "Open MPI|OpenRTE")
      list(APPEND _tumble_bench_mpiexec_flags --oversubscribe --bind-to none)
    endif()
    list(JOIN _tumble_bench_mpiexec_flags " " _tumble_bench_mpiexec_flags)
    target_compile_definitions(tumble_bench PRIVATE
      "TUMBLE_BENCH_MPI=\"$<TARGET_FILE:tumble_bench_mpi>\""
      "TUMBLE_BENCH_MPIEXEC=\"${MPIEXEC_EXECUTABLE}\""
      "TUMBLE_BENCH_MPIEXEC_NUMPROC_FLAG=\"${MPIEXEC_NUMPROC_FLAG}\""
      "TUMBLE_BENCH_MPIEXEC_PREFLAGS=\"${_tumble_bench_mpiexec_flags}\"")
    message(STATUS "tumble_bench: the ensemble study runs over MPI ranks too (tumble_bench_mpi)")
  else()
    message(STATUS "tumble_bench: without tumble::mpi (the ensemble study's MPI runs are skipped)")
  endif()
else()
  message(STATUS "tumble_bench: without tumble::ensemble or tumble::odeint (no ensemble study)")
endif()

string(TOUPPER "${CMAKE_BUILD_TYPE}" _tumble_wp_bt)
string(STRIP "${CMAKE_CXX_FLAGS} ${CMAKE_CXX_FLAGS_${_tumble_wp_bt}}" _tumble_wp_flags)
if(TUMBLE_BENCH_NATIVE)
  target_compile_options(tumble_bench PRIVATE -march=native)
  string(APPEND _tumble_wp_flags " -march=native")
endif()
if(NOT CMAKE_BUILD_TYPE)
  set(_tumble_wp_build_type "none")
else()
  set(_tumble_wp_build_type "${CMAKE_BUILD_TYPE}")
endif()
target_compile_definitions(tumble_bench PRIVATE
  "TUMBLE_BENCH_DEFAULT_OUT=\"${PROJECT_BINARY_DIR}/benchmark-results\""
  "TUMBLE_BENCH_PLOT_SCRIPT=\"${CMAKE_CURRENT_SOURCE_DIR}/main/plot.py\""
  "TUMBLE_BENCH_PLOT_PYTHON=\"${TUMBLE_BENCH_PLOT_PYTHON}\""
  "TUMBLE_BENCH_BUILD_TYPE=\"${_tumble_wp_build_type}\""
  "TUMBLE_BENCH_CXX_FLAGS=\"${_tumble_wp_flags}\"")

if(TUMBLE_BENCH_HAVE_MUJOCO AND TARGET tumble_bench_mujoco)
  set_source_files_properties(peers/mujoco_work_precision.cpp peers/mujoco_mechanisms.cpp
    PROPERTIES COMPILE_DEFINITIONS TUMBLE_BENCH_HAVE_MUJOCO=1)
  target_link_libraries(tumble_bench PRIVATE tumble_bench_mujoco)
  message(STATUS "tumble_bench: MuJoCo's RK4 is one of the references")
endif()
if(TUMBLE_BENCH_HAVE_EXUDYN)
  # Study (e) runs peers/exudyn_mechanisms.py with the Python that imports exudyn.
  set_source_files_properties(peers/exudyn_mechanisms.cpp PROPERTIES COMPILE_DEFINITIONS
    "TUMBLE_BENCH_EXUDYN_PYTHON=\"${TUMBLE_BENCH_PYTHON}\";TUMBLE_BENCH_EXUDYN_SCRIPT=\"${CMAKE_CURRENT_SOURCE_DIR}/peers/exudyn_mechanisms.py\"")
  message(STATUS "tumble_bench: Exudyn's implicit solvers run the mechanisms' study (e)")
endif()
if(TUMBLE_BENCH_HAVE_PINOCCHIO AND TARGET tumble_bench_pinocchio)
  # Only the Pinocchio translation unit sees its headers (they take a while to compile).
  set_source_files_properties(peers/pinocchio_work_precision.cpp peers/pinocchio_mechanisms.cpp
    PROPERTIES COMPILE_DEFINITIONS TUMBLE_BENCH_HAVE_PINOCCHIO=1)
  target_link_libraries(tumble_bench PRIVATE tumble_bench_pinocchio)
  message(STATUS "tumble_bench: Pinocchio's aba in CVODE is one of the references")
else()
  message(STATUS "tumble_bench: without Pinocchio (its reference is skipped)")
endif()

# The micro-benchmarks run first in tumble_bench (their medians are its table (a)): build them with it.
if(TARGET tumble_micro)
  add_dependencies(tumble_bench tumble_micro)
  target_compile_definitions(tumble_bench PRIVATE
    "TUMBLE_BENCH_MICRO=\"$<TARGET_FILE:tumble_micro>\""
    "TUMBLE_BENCH_MICRO_SCRIPT=\"${TUMBLE_MICRO_SUMMARIZE}\"")
endif()
