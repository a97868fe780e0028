# tumble's benchmarks, peers' detection: Pinocchio, MuJoCo and Exudyn as installed by pip
# (optional).
# Included by benchmarks/CMakeLists.txt, in its scope, before the studies that use them.
#
# `pip install pin` ships Pinocchio's headers under site-packages/cmeel.prefix, `pip install
# mujoco` ships libmujoco and its headers in the mujoco package; both are looked up through the
# python3 on PATH (and CMAKE_PREFIX_PATH for other installs). Results, used by
# micro/micro.cmake and main/tumble_bench.cmake (included after this file, in the same scope):
#   TUMBLE_BENCH_HAVE_PINOCCHIO  ON when found; link tumble_bench_pinocchio (header-only)
#   TUMBLE_BENCH_HAVE_MUJOCO     ON when found; link tumble_bench_mujoco
#   TUMBLE_BENCH_HAVE_EXUDYN     ON when TUMBLE_BENCH_PYTHON can `import exudyn, numpy`: study (e)
#                                runs peers/exudyn_mechanisms.py with that Python (Exudyn has no
#                                C or C++ interface; nothing is linked)
find_program(TUMBLE_BENCH_PYTHON NAMES python3 python DOC "python used to locate pip-installed peers")

set(TUMBLE_BENCH_HAVE_PINOCCHIO OFF)
if(NOT TUMBLE_BENCH_PINOCCHIO STREQUAL "OFF")
  # Pinocchio is used header-only (its algorithms compiled with tumble's compiler and flags), so
  # only its headers and Boost's are needed. Its CMake config is not loaded: the pip wheel's
  # config requires urdfdom_headers, OpenMP and more, which the wheel does not all provide, and a
  # failed find_dependency(... REQUIRED) inside it would stop the whole configure.
  set(_tumble_cmeel "")
  if(TUMBLE_BENCH_PYTHON)
    execute_process(COMMAND ${TUMBLE_BENCH_PYTHON} -m cmeel cmake
                    OUTPUT_VARIABLE _tumble_cmeel ERROR_QUIET OUTPUT_STRIP_TRAILING_WHITESPACE)
  endif()
  find_path(TUMBLE_PINOCCHIO_INCLUDE_DIR pinocchio/algorithm/aba.hpp
            HINTS "${_tumble_cmeel}/include" PATH_SUFFIXES include)
  find_path(TUMBLE_PINOCCHIO_BOOST_INCLUDE_DIR boost/mpl/vector.hpp
            HINTS "${TUMBLE_PINOCCHIO_INCLUDE_DIR}" "${_tumble_cmeel}/include")
  if(TUMBLE_PINOCCHIO_INCLUDE_DIR AND TUMBLE_PINOCCHIO_BOOST_INCLUDE_DIR)
    set(TUMBLE_BENCH_HAVE_PINOCCHIO ON)
    file(STRINGS "${TUMBLE_PINOCCHIO_INCLUDE_DIR}/pinocchio/config.hpp" _tumble_pin_version
         REGEX "define PINOCCHIO_VERSION \"")
    string(REGEX MATCH "[0-9]+\\.[0-9]+\\.[0-9]+" _tumble_pin_version "${_tumble_pin_version}")
    if(NOT TARGET tumble_bench_pinocchio)
      add_library(tumble_bench_pinocchio INTERFACE)
      target_include_directories(tumble_bench_pinocchio SYSTEM INTERFACE
                                 "${TUMBLE_PINOCCHIO_INCLUDE_DIR}"
                                 "${TUMBLE_PINOCCHIO_BOOST_INCLUDE_DIR}")
      # What pinocchio::pinocchio_headers defines (Pinocchio's joint variants need them).
      target_compile_definitions(tumble_bench_pinocchio INTERFACE
        BOOST_MPL_LIMIT_LIST_SIZE=30 BOOST_MPL_LIMIT_VECTOR_SIZE=30
        BOOST_MPL_CFG_NO_PREPROCESSED_HEADERS BOOST_FUSION_INVOKE_MAX_ARITY=12)
      target_link_libraries(tumble_bench_pinocchio INTERFACE Eigen3::Eigen)
    endif()
    message(STATUS "tumble benchmarks: Pinocchio ${_tumble_pin_version} found, header-only "
                   "(${TUMBLE_PINOCCHIO_INCLUDE_DIR})")
  elseif(TUMBLE_BENCH_PINOCCHIO STREQUAL "ON")
    message(FATAL_ERROR "tumble benchmarks: TUMBLE_BENCH_PINOCCHIO=ON but Pinocchio's headers "
                        "were not found (pip install pin, or add its prefix to CMAKE_PREFIX_PATH)")
  else()
    message(STATUS "tumble benchmarks: Pinocchio not found, its comparisons are skipped "
                   "(pip install pin to add them)")
  endif()
endif()

set(TUMBLE_BENCH_HAVE_MUJOCO OFF)
if(NOT TUMBLE_BENCH_MUJOCO STREQUAL "OFF")
  set(_tumble_mujoco_hint "")
  if(TUMBLE_BENCH_PYTHON)
    execute_process(COMMAND ${TUMBLE_BENCH_PYTHON} -c
                            "import mujoco, os; print(os.path.dirname(mujoco.__file__))"
                    OUTPUT_VARIABLE _tumble_mujoco_hint ERROR_QUIET
                    OUTPUT_STRIP_TRAILING_WHITESPACE)
  endif()
  find_path(TUMBLE_MUJOCO_INCLUDE_DIR mujoco/mujoco.h HINTS "${_tumble_mujoco_hint}/include")
  # The wheel ships only the versioned file (libmujoco.so.X.Y.Z), which find_library ignores.
  find_library(TUMBLE_MUJOCO_LIBRARY NAMES mujoco HINTS "${_tumble_mujoco_hint}")
  if(NOT TUMBLE_MUJOCO_LIBRARY AND _tumble_mujoco_hint)
    file(GLOB _tumble_mujoco_libs "${_tumble_mujoco_hint}/libmujoco.so*"
                                  "${_tumble_mujoco_hint}/libmujoco*.dylib")
    if(_tumble_mujoco_libs)
      list(GET _tumble_mujoco_libs 0 _tumble_mujoco_lib)
      set(TUMBLE_MUJOCO_LIBRARY "${_tumble_mujoco_lib}" CACHE FILEPATH "libmujoco" FORCE)
    endif()
  endif()
  if(TUMBLE_MUJOCO_INCLUDE_DIR AND TUMBLE_MUJOCO_LIBRARY)
    set(TUMBLE_BENCH_HAVE_MUJOCO ON)
    if(NOT TARGET tumble_bench_mujoco)
      add_library(tumble_bench_mujoco SHARED IMPORTED)
      set_target_properties(tumble_bench_mujoco PROPERTIES
        IMPORTED_LOCATION "${TUMBLE_MUJOCO_LIBRARY}"
        INTERFACE_INCLUDE_DIRECTORIES "${TUMBLE_MUJOCO_INCLUDE_DIR}")
    endif()
    message(STATUS "tumble benchmarks: MuJoCo found (${TUMBLE_MUJOCO_LIBRARY})")
  elseif(TUMBLE_BENCH_MUJOCO STREQUAL "ON")
    message(FATAL_ERROR "tumble benchmarks: TUMBLE_BENCH_MUJOCO=ON but MuJoCo was not found "
                        "(pip install mujoco)")
  else()
    message(STATUS "tumble benchmarks: MuJoCo not found, its comparison is skipped "
                   "(pip install mujoco to add it)")
  endif()
endif()

# Exudyn (`pip install exudyn`): a Python package over a C++ core, run by study (e) as a Python
# process (peers/exudyn_mechanisms.cpp). Its import is tried from the build directory, so that no
# folder of the source tree shadows a module.
set(TUMBLE_BENCH_EXUDYN "AUTO" CACHE STRING
    "Compare with Exudyn in the mechanisms' study (AUTO, ON, OFF)")
set_property(CACHE TUMBLE_BENCH_EXUDYN PROPERTY STRINGS AUTO ON OFF)
set(TUMBLE_BENCH_HAVE_EXUDYN OFF)
if(NOT TUMBLE_BENCH_EXUDYN STREQUAL "OFF")
  set(_tumble_exudyn_version "")
  set(_tumble_exudyn_status 1)
  if(TUMBLE_BENCH_PYTHON)
    execute_process(COMMAND ${TUMBLE_BENCH_PYTHON} -c
                            "import exudyn, numpy; print('exudyn', exudyn.__version__)"
                    WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}"
                    RESULT_VARIABLE _tumble_exudyn_status
                    OUTPUT_VARIABLE _tumble_exudyn_version ERROR_QUIET
                    OUTPUT_STRIP_TRAILING_WHITESPACE)
  endif()
  string(REGEX MATCH "exudyn [0-9][^ \n]*" _tumble_exudyn_version "${_tumble_exudyn_version}")
  if(_tumble_exudyn_status EQUAL 0 AND _tumble_exudyn_version)
    set(TUMBLE_BENCH_HAVE_EXUDYN ON)
    message(STATUS "tumble benchmarks: ${_tumble_exudyn_version} found (${TUMBLE_BENCH_PYTHON})")
  elseif(TUMBLE_BENCH_EXUDYN STREQUAL "ON")
    message(FATAL_ERROR "tumble benchmarks: TUMBLE_BENCH_EXUDYN=ON but '${TUMBLE_BENCH_PYTHON}' "
                        "cannot import exudyn and numpy (pip install exudyn, and set "
                        "TUMBLE_BENCH_PYTHON to that Python)")
  else()
    message(STATUS "tumble benchmarks: Exudyn not found, its comparison is skipped "
                   "(pip install exudyn, TUMBLE_BENCH_PYTHON=that python, to add it)")
  endif()
endif()
