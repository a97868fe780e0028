# Install rules and the CMake package: find_package(tumble CONFIG) then provides tumble::tumble
# and, when tumble was installed with CVODE support and SUNDIALS is found again on the consumer's
# machine, tumble::cvode (component `cvode`); likewise tumble::odeint (component `odeint`, Boost
# headers >= 1.74), tumble::ensemble (component `ensemble`, oneTBB) and tumble::mpi (component
# `mpi`, tumble::ensemble and MPI). Included from the top-level CMakeLists.txt when
# TUMBLE_INSTALL is on (the default only when tumble is the top-level project).
#
# Layout under the prefix:
#   include/tumble/...                       the headers
#   share/cmake/tumble/tumbleConfig.cmake    (+ ConfigVersion, Targets, and for CVODE:
#                                             CvodeTargets and tumbleFindSundials.cmake)
#   share/doc/tumble/LICENSE
# The package is architecture independent (header-only), hence share/ and ARCH_INDEPENDENT.
include(CMakePackageConfigHelpers)

set(TUMBLE_INSTALL_CMAKEDIR "${CMAKE_INSTALL_DATADIR}/cmake/tumble"
    CACHE STRING "Where tumble's CMake package files are installed, relative to the prefix")

install(DIRECTORY "${PROJECT_SOURCE_DIR}/include/" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}")
install(FILES "${PROJECT_SOURCE_DIR}/LICENSE" DESTINATION "${CMAKE_INSTALL_DATADIR}/doc/tumble")

install(TARGETS tumble EXPORT tumbleTargets)
install(EXPORT tumbleTargets NAMESPACE tumble:: DESTINATION "${TUMBLE_INSTALL_CMAKEDIR}")

# tumble::cvode goes into its own export set, which tumbleConfig.cmake loads only after it has
# found SUNDIALS on the consumer's machine. Its SUNDIALS link targets are not exported (they are
# BUILD_INTERFACE-only in CMakeLists.txt): their names depend on the SUNDIALS release (6 vs 7)
# and on how it was found, so the config resolves them again with the same macro the build used.
if(TARGET tumble_cvode)
  set(TUMBLE_INSTALLED_CVODE ON)
  install(TARGETS tumble_cvode EXPORT tumbleCvodeTargets)
  install(EXPORT tumbleCvodeTargets NAMESPACE tumble:: DESTINATION "${TUMBLE_INSTALL_CMAKEDIR}")
  install(FILES "${PROJECT_SOURCE_DIR}/cmake/tumbleFindSundials.cmake"
          DESTINATION "${TUMBLE_INSTALL_CMAKEDIR}")
else()
  set(TUMBLE_INSTALLED_CVODE OFF)
endif()

# tumble::odeint likewise: its Boost::headers link is BUILD_INTERFACE-only, and the config adds
# it again after finding Boost on the consumer's machine.
if(TARGET tumble_odeint)
  set(TUMBLE_INSTALLED_ODEINT ON)
  install(TARGETS tumble_odeint EXPORT tumbleOdeintTargets)
  install(EXPORT tumbleOdeintTargets NAMESPACE tumble:: DESTINATION "${TUMBLE_INSTALL_CMAKEDIR}")
else()
  set(TUMBLE_INSTALLED_ODEINT OFF)
endif()

# tumble::ensemble likewise: its TBB::tbb link is BUILD_INTERFACE-only, and the config adds it
# again after finding TBB on the consumer's machine.
if(TARGET tumble_ensemble)
  set(TUMBLE_INSTALLED_ENSEMBLE ON)
  install(TARGETS tumble_ensemble EXPORT tumbleEnsembleTargets)
  install(EXPORT tumbleEnsembleTargets NAMESPACE tumble:: DESTINATION "${TUMBLE_INSTALL_CMAKEDIR}")
else()
  set(TUMBLE_INSTALLED_ENSEMBLE OFF)
endif()

# tumble::mpi likewise: its MPI::MPI_CXX link is BUILD_INTERFACE-only, and the config adds it
# again after finding MPI on the consumer's machine (and the component ensemble it builds on).
if(TARGET tumble_mpi)
  set(TUMBLE_INSTALLED_MPI ON)
  install(TARGETS tumble_mpi EXPORT tumbleMpiTargets)
  install(EXPORT tumbleMpiTargets NAMESPACE tumble:: DESTINATION "${TUMBLE_INSTALL_CMAKEDIR}")
else()
  set(TUMBLE_INSTALLED_MPI OFF)
endif()

configure_package_config_file(
  "${PROJECT_SOURCE_DIR}/cmake/tumbleConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/tumbleConfig.cmake"
  INSTALL_DESTINATION "${TUMBLE_INSTALL_CMAKEDIR}")
write_basic_package_version_file(
  "${PROJECT_BINARY_DIR}/tumbleConfigVersion.cmake"
  VERSION "${PROJECT_VERSION}"
  COMPATIBILITY SameMajorVersion
  ARCH_INDEPENDENT)
install(FILES "${PROJECT_BINARY_DIR}/tumbleConfig.cmake"
              "${PROJECT_BINARY_DIR}/tumbleConfigVersion.cmake"
        DESTINATION "${TUMBLE_INSTALL_CMAKEDIR}")
