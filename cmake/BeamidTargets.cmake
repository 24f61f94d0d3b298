# Small helpers shared by the folders: one library per folder, one test
# executable per *_test.cc, one benchmark executable per *_benchmark.cc.

# Designated initialisers may leave members at their defaults: that is the
# point of options structs, so that warning is off.
# GCC 12 reports false -Wrestrict positives inside std::string (GCC PR 105329);
# clang (the fuzz build) has no such option.
set(BEAMID_WARNINGS -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wno-missing-field-initializers)
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  list(APPEND BEAMID_WARNINGS -Wno-restrict)
endif()

# beamid_add_folder_library(NAME <target> FOLDER <dir> [DEPS ...] [OWN_UNIT <file.cc> ...])
# Compiles every .cc of the folder (and its internal/) into one library, so a
# new concept is one new file and no list needs editing.
# With -DBEAMID_UNITY_BUILD=ON (what CI builds) the library's files are
# compiled BEAMID_UNITY_BATCH at a time, one translation unit each batch, so
# the heavy headers (Eigen, nlohmann/json, fmt) are parsed once per batch
# rather than once per file. Two files whose anonymous namespaces define the
# same name cannot share a unit: list one of them under OWN_UNIT (paths
# relative to FOLDER) and it is compiled on its own.
function(beamid_add_folder_library)
  cmake_parse_arguments(ARG "" "NAME;FOLDER" "DEPS;OWN_UNIT" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${ARG_FOLDER}/*.cc ${ARG_FOLDER}/internal/*.cc)
  if(NOT sources)
    # A folder whose concepts are all header-only still gets its target.
    add_library(${ARG_NAME} INTERFACE)
    target_include_directories(${ARG_NAME} INTERFACE ${PROJECT_SOURCE_DIR})
    target_link_libraries(${ARG_NAME} INTERFACE ${ARG_DEPS})
    return()
  endif()
  add_library(${ARG_NAME} ${BEAMID_LIBRARY_TYPE} ${sources})
  if(BEAMID_UNITY_BUILD)
    set_target_properties(${ARG_NAME} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${BEAMID_UNITY_BATCH})
    foreach(file ${ARG_OWN_UNIT})
      set_source_files_properties(${ARG_FOLDER}/${file} PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
    endforeach()
  endif()
  target_include_directories(${ARG_NAME} PUBLIC ${PROJECT_SOURCE_DIR})
  target_compile_options(${ARG_NAME} PRIVATE ${BEAMID_WARNINGS})
  target_link_libraries(${ARG_NAME} PUBLIC ${ARG_DEPS})
endfunction()

# beamid_add_test_headers(LIBS ...): with -DBEAMID_PRECOMPILE_TEST_HEADERS=ON
# (what CI builds) the headers every test parses (GoogleTest, Eigen,
# nlohmann/json, fmt, the standard library) are compiled once, by this
# target, and every test executable reuses the result. Off by default:
# ccache does not cache a compile that reads a precompiled header.
function(beamid_add_test_headers)
  cmake_parse_arguments(ARG "" "" "LIBS" ${ARGN})
  if(NOT BEAMID_PRECOMPILE_TEST_HEADERS)
    return()
  endif()
  # Built with the tests' flags: a precompiled header serves only compiles
  # whose flags match the ones it was made with.
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/test_headers.cc "// The precompiled headers of the tests.\n")
  add_library(beamid_test_headers OBJECT ${CMAKE_CURRENT_BINARY_DIR}/test_headers.cc)
  target_compile_options(beamid_test_headers PRIVATE ${BEAMID_WARNINGS} -Werror)
  target_include_directories(beamid_test_headers PRIVATE ${PROJECT_SOURCE_DIR})
  target_link_libraries(beamid_test_headers PRIVATE ${ARG_LIBS} GTest::gtest GTest::gtest_main)
  target_precompile_headers(beamid_test_headers PRIVATE
    <algorithm> <cmath> <complex> <cstdio> <filesystem> <fstream> <functional>
    <numbers> <random> <sstream> <string> <vector>
    <Eigen/Core> <Eigen/LU> <nlohmann/json.hpp> <fmt/format.h>
    <gtest/gtest.h> <gmock/gmock.h>)
endfunction()

# beamid_add_test(<source> LIBS ...): one GoogleTest executable named after the
# file, each test case a ctest test (but see SetUpTestSuite below). Files named *_slow_test.cc get the ctest label "slow", all others
# "fast" (the sanitizer CI job runs the fast ones).
function(beamid_add_test source)
  cmake_parse_arguments(ARG "" "" "LIBS" ${ARGN})
  get_filename_component(name ${source} NAME_WE)
  get_filename_component(folder ${source} DIRECTORY)
  get_filename_component(folder ${folder} NAME)
  set(target ${folder}_${name})
  add_executable(${target} ${source})
  target_compile_options(${target} PRIVATE ${BEAMID_WARNINGS} -Werror)
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR})
  target_link_libraries(${target} PRIVATE ${ARG_LIBS} GTest::gtest GTest::gtest_main)
  if(BEAMID_PRECOMPILE_TEST_HEADERS)
    target_precompile_headers(${target} REUSE_FROM beamid_test_headers)
  endif()
  if(name MATCHES "_slow_test$")
    set(label slow)
  else()
    set(label fast)
    # beamid_fast_tests (tests/CMakeLists.txt) builds only these: the
    # sanitizer CI job runs the fast tests and need not compile the slow ones.
    set_property(GLOBAL APPEND PROPERTY BEAMID_FAST_TESTS ${target})
  endif()
  # A suite that builds its data once (SetUpTestSuite: a simulated campaign,
  # an identification) runs as one ctest test: one process per test case
  # would build the data again for each.
  file(READ ${source} text)
  if(text MATCHES "SetUpTestSuite")
    add_test(NAME ${target} COMMAND ${target} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
    set_tests_properties(${target} PROPERTIES LABELS ${label})
  else()
    gtest_discover_tests(${target}
      WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
      PROPERTIES LABELS ${label}
      DISCOVERY_TIMEOUT 60)
  endif()
endfunction()
