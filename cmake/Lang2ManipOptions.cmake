# Compiler warnings, sanitizers and the helpers that declare modules and tests.

# Unity builds: each target compiles its sources in batches, so the heavy headers (Eigen, JSON,
# CLI11, OMPL, FCL, gtest) are parsed once per batch instead of once per file: about a third of
# the compile time. Sources therefore must not repeat a name in their anonymous namespaces.
option(LANG2MANIP_UNITY_BUILD "Compile each target's sources in batches (faster builds)" ON)
set(CMAKE_UNITY_BUILD ${LANG2MANIP_UNITY_BUILD})
set(CMAKE_UNITY_BUILD_BATCH_SIZE 8)

add_library(lang2manip_warnings INTERFACE)
target_compile_options(lang2manip_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast -Wcast-align
  -Wunused -Woverloaded-virtual -Wconversion -Wno-sign-conversion
  -Wdouble-promotion -Wformat=2 -Wimplicit-fallthrough
  # GCC 12 reports false -Wrestrict positives inside std::string concatenation (GCC PR 105329).
  $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>)
if(LANG2MANIP_WERROR)
  target_compile_options(lang2manip_warnings INTERFACE -Werror)
endif()

if(LANG2MANIP_SANITIZE)
  # -O1 keeps the Debug build's assertions (Eigen's index checks among them) but runs the
  # planning and IK loops several times faster than -O0; the sanitizers see the same code.
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined -O1)
  # GCC 12 with the sanitizers at -O1 reports false -Wmaybe-uninitialized in libstdc++'s <regex>
  # (GCC's manual warns that the sanitizers can cause false warnings).
  target_compile_options(lang2manip_warnings INTERFACE $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>)
  add_link_options(-fsanitize=address,undefined)
  # Eigen 3.4 switches to its own offset-pointer aligned_malloc under AddressSanitizer; Debian's
  # liborocos-kdl (not instrumented) then frees our Eigen buffers with plain free() (bad-free in
  # KDL's LMA solver). glibc's malloc already gives Eigen's 16-byte alignment here.
  add_compile_definitions(EIGEN_MALLOC_ALREADY_ALIGNED=1)
endif()

if(LANG2MANIP_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "LANG2MANIP_FUZZ needs clang (libFuzzer): configure with "
                        "-DCMAKE_CXX_COMPILER=clang++ (or run `make fuzz`)")
  endif()
  if(LANG2MANIP_SANITIZE)
    message(FATAL_ERROR "LANG2MANIP_FUZZ already builds with the sanitizers; drop LANG2MANIP_SANITIZE")
  endif()
  # Every library is instrumented for libFuzzer's coverage and checked by ASan and UBSan (UB
  # aborts, so the fuzzer reports it); the harnesses add -fsanitize=fuzzer (fuzz/CMakeLists.txt).
  # -O1 with assertions on, as the sanitized test build; line tables are all the sanitizers'
  # stack traces need and compile much faster than full debug information.
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
                      -fno-omit-frame-pointer -O1 -gline-tables-only)
  # Clang's -Wdouble-promotion also reports float -> double initializations (assimp and Coin
  # hand out floats), which GCC's does not; the fuzz build is not the place for that check.
  target_compile_options(lang2manip_warnings INTERFACE -Wno-double-promotion)
  add_link_options(-fsanitize=address,undefined)
  add_compile_definitions(EIGEN_MALLOC_ALREADY_ALIGNED=1)  # see LANG2MANIP_SANITIZE above
endif()

# lang2manip_add_module(NAME SOURCES ... DEPENDS ...)
# One module = one directory = one library named lang2manip_<NAME>; sources listed explicitly.
function(lang2manip_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS;PRIVATE_DEPENDS" ${ARGN})
  add_library(lang2manip_${name} ${ARG_SOURCES})
  add_library(lang2manip::${name} ALIAS lang2manip_${name})
  target_include_directories(lang2manip_${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/src>)
  target_link_libraries(lang2manip_${name} PUBLIC ${ARG_DEPENDS}
                        PRIVATE ${ARG_PRIVATE_DEPENDS} lang2manip_warnings)
endfunction()

# lang2manip_add_test(NAME SOURCES ... DEPENDS ...): one gtest binary, tests discovered by CTest.
function(lang2manip_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  target_link_libraries(${name} PRIVATE ${ARG_DEPENDS} GTest::gtest_main GTest::gmock
                        lang2manip_warnings)
  target_compile_definitions(${name} PRIVATE
    LANG2MANIP_SHARED_DIR="${LANG2MANIP_SHARED_DIR}"
    LANG2MANIP_TEST_DATA_DIR="${PROJECT_SOURCE_DIR}/tests/data")
  # Allowed-collision matrices kept on disk by the tests go to the build tree, not the user's cache.
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300
    ENVIRONMENT "LANG2MANIP_CACHE_DIR=${CMAKE_BINARY_DIR}/test-cache")
endfunction()
