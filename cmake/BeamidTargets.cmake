# Small helpers shared by the folders: one library per folder, one test
# executable per *_test.cc, one benchmark executable per *_benchmark.cc.

# Designated initialisers may leave members at their defaults: that is the
# point of options structs, so that warning is off.
# GCC 12 reports false -Wrestrict positives inside std::string (GCC PR
# 105329); clang (the fuzz build) has no such option.
set(BEAMID_WARNINGS -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wno-missing-field-initializers)
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  list(APPEND BEAMID_WARNINGS -Wno-restrict)
endif()

# Precompiled headers: parsing the same standard, Eigen, fmt and JSON headers
# again was up to half of a file's compile time (54 % of cli_test.cc's). One header for the folder
# libraries, which share their compile flags, one for the program and one
# for the tests, with GoogleTest's headers as well (a test's compile time
# 7.3 s → 4.9 s). The tests build with -Werror, and with a precompiled
# header GCC 12 reports its false positives inside the system headers as
# the tests' own (below; std::regex's -Wmaybe-uninitialized under the
# sanitizers): those are off for the tests that use it. The fuzz build
# compiles its readers with other flags than the rest, so it has none.
option(BEAMID_PRECOMPILE_HEADERS "Precompile the common system headers" ON)
set(BEAMID_LIBRARY_PCH <algorithm> <cmath> <complex> <filesystem> <functional> <map> <memory>
    <optional> <string> <string_view> <vector> <Eigen/Core> <fmt/format.h> <nlohmann/json.hpp>)
if(BEAMID_FUZZ)
  set(BEAMID_PRECOMPILE_HEADERS OFF)
endif()
# With a precompiled header GCC 12 no longer knows that std::string's inlined
# memcpy is a system header's code and reports its false -Wstringop-overflow
# and -Warray-bounds positives (GCC PR 105651) in every `"text" + string`:
# off for the targets that use one.
set(BEAMID_PCH_WARNINGS)
set(BEAMID_TEST_PCH_WARNINGS)
if(BEAMID_PRECOMPILE_HEADERS AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  set(BEAMID_PCH_WARNINGS -Wno-stringop-overflow -Wno-array-bounds)
  set(BEAMID_TEST_PCH_WARNINGS ${BEAMID_PCH_WARNINGS} -Wno-maybe-uninitialized)
endif()
set(BEAMID_TEST_PCH ${BEAMID_LIBRARY_PCH} <gtest/gtest.h> <gmock/gmock.h>)

# Unity build: a folder's files are compiled eight to a translation unit.
# Eigen's decompositions and products, instantiated and optimised once per
# file otherwise, are then done once per eight (solver/diagnosis: 93 s of
# CPU file by file, 50 s so). A file's own helpers therefore carry names no
# other file of its folder uses. The fuzz build compiles its readers, which
# get flags of their own, file by file, and the rest in batches.
option(BEAMID_UNITY_BUILD "Compile each folder's files eight to a translation unit" ON)
function(beamid_unity_build target)
  if(BEAMID_UNITY_BUILD)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
  endif()
endfunction()

# beamid_share_precompiled_header(<target> <host property> <may host> <headers>...):
# targets that share their compile flags share one precompiled header. The
# first that may host it compiles it and is recorded in the global
# property; the later ones load it.
function(beamid_share_precompiled_header target host_property may_host)
  get_property(pch_host GLOBAL PROPERTY ${host_property})
  if(pch_host)
    target_precompile_headers(${target} REUSE_FROM ${pch_host})
  else()
    target_precompile_headers(${target} PRIVATE ${ARGN})
    if(may_host)
      set_property(GLOBAL PROPERTY ${host_property} ${target})
    endif()
  endif()
endfunction()

# Headers are included from the top of the sources ("hb/scenario.h"), and
# from include/beamid of an installed copy (cmake/BeamidInstall.cmake).
set(BEAMID_INCLUDE_DIRECTORIES $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}> $<INSTALL_INTERFACE:include/beamid>)

# beamid_add_folder_library(NAME <target> FOLDER <dir> [DEPS ...])
# Compiles every .cc of the folder (and its internal/) into one library, so a
# new concept is one new file and no list needs editing.
function(beamid_add_folder_library)
  cmake_parse_arguments(ARG "" "NAME;FOLDER" "DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${ARG_FOLDER}/*.cc ${ARG_FOLDER}/internal/*.cc)
  if(NOT sources)
    # A folder whose concepts are all header-only still gets its target.
    add_library(${ARG_NAME} INTERFACE)
    target_include_directories(${ARG_NAME} INTERFACE ${BEAMID_INCLUDE_DIRECTORIES})
    target_link_libraries(${ARG_NAME} INTERFACE ${ARG_DEPS})
    return()
  endif()
  add_library(${ARG_NAME} ${BEAMID_LIBRARY_TYPE} ${sources})
  if(BEAMID_FUZZ)
    # The readers of files under UBSan and the fuzzer's coverage as well (CMakeLists.txt).
    foreach(source ${sources})
      if(source MATCHES "${BEAMID_READER_SOURCES}")
        set_property(SOURCE ${source} PROPERTY SKIP_UNITY_BUILD_INCLUSION ON)
        set_property(SOURCE ${source} APPEND PROPERTY COMPILE_OPTIONS
                     -O1 -fsanitize=fuzzer-no-link,undefined -fno-sanitize-recover=undefined)
      endif()
    endforeach()
  endif()
  target_include_directories(${ARG_NAME} PUBLIC ${BEAMID_INCLUDE_DIRECTORIES})
  target_compile_options(${ARG_NAME} PRIVATE ${BEAMID_WARNINGS})
  target_link_libraries(${ARG_NAME} PUBLIC ${ARG_DEPS})
  beamid_unity_build(${ARG_NAME})
  if(BEAMID_PRECOMPILE_HEADERS)
    # The folder libraries share their flags: the first one (hb) compiles
    # the header, the others load it. A shared library (the sanitizer build)
    # would define its own <target>_EXPORTS, which no file uses and which
    # makes GCC refuse another library's header.
    set_target_properties(${ARG_NAME} PROPERTIES DEFINE_SYMBOL "")
    target_compile_options(${ARG_NAME} PRIVATE ${BEAMID_PCH_WARNINGS})
    beamid_share_precompiled_header(${ARG_NAME} BEAMID_LIBRARY_PCH_HOST TRUE ${BEAMID_LIBRARY_PCH})
  endif()
endfunction()

# beamid_add_test(<source> [TIMEOUT_S <s>] LIBS ...): one GoogleTest executable
# named after the file, each test case a ctest test (but see SetUpTestSuite
# below). Files named *_slow_test.cc get the ctest label "slow", all others
# "fast" (the sanitizer CI job runs the fast ones). TIMEOUT_S: a study that
# runs longer than ctest's default timeout (scripts/test.sh) states its own.
function(beamid_add_test source)
  cmake_parse_arguments(ARG "" "TIMEOUT_S" "LIBS" ${ARGN})
  get_filename_component(name ${source} NAME_WE)
  get_filename_component(folder ${source} DIRECTORY)
  get_filename_component(folder ${folder} NAME)
  set(target ${folder}_${name})
  add_executable(${target} ${source})
  target_compile_options(${target} PRIVATE ${BEAMID_WARNINGS} -Werror)
  # The tests' own code is compiled at -O1: their work runs in the
  # libraries (optimised as the build type says), and -O1 halves the compile
  # time of the GoogleTest-heavy files. Under the sanitizers, which
  # instrument every expression, at -Og: cli_test.cc compiles in 18 s
  # instead of 30 s there, and a test that computes in its own code (a
  # Monte Carlo over Eigen matrices) runs 2.3 s where -O0 takes 14 s.
  if(BEAMID_SANITIZE)
    target_compile_options(${target} PRIVATE -Og)
  else()
    target_compile_options(${target} PRIVATE -O1)
  endif()
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR})
  target_link_libraries(${target} PRIVATE ${ARG_LIBS} GTest::gtest GTest::gtest_main)
  if(name MATCHES "_slow_test$")
    set(label slow)
  else()
    set(label fast)
    # beamid_fast_tests (tests/CMakeLists.txt) builds only these: the
    # sanitizer CI job runs the fast tests and need not compile the slow ones.
    set_property(GLOBAL APPEND PROPERTY BEAMID_FAST_TESTS ${target})
  endif()
  if(BEAMID_PRECOMPILE_HEADERS)
    # Every test shares its flags: the first fast one compiles the header
    # (the sanitizer job builds the fast ones only), the others load it.
    target_compile_options(${target} PRIVATE ${BEAMID_TEST_PCH_WARNINGS})
    string(COMPARE EQUAL "${label}" "fast" may_host)
    beamid_share_precompiled_header(${target} BEAMID_TEST_PCH_HOST ${may_host} ${BEAMID_TEST_PCH})
  endif()
  # A slow test starts before every fast one, and a slow suite run as one
  # process (below) before a slow test case (ctest runs the costliest
  # first): a two-minute test started last would run alone at the end, on
  # one core of two. After a first run ctest orders by measured times.
  if(ARG_TIMEOUT_S)
    set(cost 1000)  # the longest of all: first
    set(timeout TIMEOUT ${ARG_TIMEOUT_S})
  elseif(label STREQUAL "slow")
    set(cost 100)
  else()
    set(cost 1)
  endif()
  # A suite that builds its data once (SetUpTestSuite: a simulated campaign,
  # an identification) runs as one ctest test: one process per test case
  # would build the data again for each.
  file(READ ${source} text)
  if(text MATCHES "SetUpTestSuite")
    math(EXPR cost "2 * ${cost}")
    add_test(NAME ${target} COMMAND ${target} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
    set_tests_properties(${target} PROPERTIES LABELS ${label} COST ${cost} ${timeout})
  else()
    gtest_discover_tests(${target}
      WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
      PROPERTIES LABELS ${label} COST ${cost} ${timeout}
      DISCOVERY_TIMEOUT 60)
  endif()
endfunction()
