# Every dependency is a Debian package (see scripts/install-deps.sh); nothing is downloaded.

find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(urdfdom REQUIRED)
find_package(assimp REQUIRED)
find_package(Coin REQUIRED)
find_package(pugixml REQUIRED)
find_package(yaml-cpp REQUIRED)
find_package(nlohmann_json 3.11 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(orocos_kdl REQUIRED)                # variables: orocos_kdl_LIBRARIES
find_package(ompl REQUIRED)                      # variables: OMPL_INCLUDE_DIRS, OMPL_LIBRARIES
# OMPL_LIBRARIES also names Boost libraries whose development links Debian does not install;
# libompl.so (its first entry) brings them in by itself.
list(GET OMPL_LIBRARIES 0 lang2manip_ompl_library)
# deps.md trap 1: libompl and liborocos-kdl export clashing Eigen instantiations, and the library
# loaded first serves both. OMPL's informed samplers (BIT*, ABIT*, AIT*, informed RRT*) crash on
# KDL's copies; KDL's FK and NR_JL IK (all lang2manip uses of KDL) run on OMPL's. So OMPL MUST be
# linked before KDL: targets take both only through this one, which lists them in that order
# (tests/kinematics/kdl_link_order_test.cpp fails otherwise).
add_library(lang2manip_ompl_then_kdl INTERFACE)
target_link_libraries(lang2manip_ompl_then_kdl INTERFACE ${lang2manip_ompl_library} ${orocos_kdl_LIBRARIES})
target_include_directories(lang2manip_ompl_then_kdl SYSTEM INTERFACE ${OMPL_INCLUDE_DIRS})
find_package(fcl REQUIRED)                       # target: fcl
# cpp-httplib has no CMake config; Debian's build is a compiled library whose header holds only
# declarations, so its compile definitions (CPPHTTPLIB_OPENSSL_SUPPORT, ...) MUST come from
# pkg-config with it: without them the class layouts differ (double free).
find_package(PkgConfig REQUIRED)
pkg_check_modules(HTTPLIB REQUIRED IMPORTED_TARGET cpp-httplib)
find_package(OpenSSL REQUIRED)                   # OpenSSL::Crypto (certificate error strings)
if(LANG2MANIP_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)               # benchmark::benchmark
endif()
if(LANG2MANIP_BUILD_TESTS)
  find_package(GTest REQUIRED)
  include(GoogleTest)
endif()
