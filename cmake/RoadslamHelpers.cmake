# Helpers shared by every library, app, test and benchmark of roadslam.

function(roadslam_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    # clang (scripts/sanitize.sh's tree) knows neither GCC warning below
  elseif(ROADSLAM_UNITY)
    # A unity batch #includes its sources, so GCC takes a class with a member from the file's anonymous
    # namespace for a header's class. Warned as usual in a -DROADSLAM_UNITY=OFF build.
    target_compile_options(${target} PRIVATE -Wno-psabi -Wno-subobject-linkage)
  else()
    target_compile_options(${target} PRIVATE -Wno-psabi)
  endif()
  if(ROADSLAM_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# roadslam_add_library(<name> SOURCES a.cpp ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# Creates target roadslam_<name> with alias roadslam::<name>; headers in include/roadslam/<name>/.
# Tests in tests/*.cpp are built into one gtest binary <name>_tests when tests are enabled.
function(roadslam_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  set(target roadslam_${name})
  add_library(${target} STATIC ${ARG_SOURCES})
  add_library(roadslam::${name} ALIAS ${target})
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>)
  target_link_libraries(${target} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  roadslam_set_warnings(${target})
endfunction()

# roadslam_add_test(<name> SOURCES ... DEPS ... [LABELS ...] [TIMEOUT s])
# One gtest executable; every TEST is registered with ctest through gtest_discover_tests.
# The environment variable ROADSLAM_SHARED_DATA points at ../shared/data for data-driven tests.
# ROADSLAM_SIM_CACHE is the build tree's one cache of simulated drives (sim::simulateCached), shared
# by every test binary.
function(roadslam_add_test name)
  if(NOT ROADSLAM_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "TIMEOUT" "SOURCES;DEPS;LABELS" ${ARGN})
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 300)
  endif()
  if(NOT ARG_LABELS)
    set(ARG_LABELS unit)
  endif()
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    ROADSLAM_SHARED_DATA="${ROADSLAM_SHARED_DATA}"
    ROADSLAM_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    ROADSLAM_BINARY_DIR="${PROJECT_BINARY_DIR}"
    ROADSLAM_SIM_CACHE="${PROJECT_BINARY_DIR}/sim-cache")
  roadslam_set_warnings(${name})
  # On a clean clone ctest has no CTestCostData.txt and starts the tests in the order they were
  # declared: a heavy test started last runs alone with a core idle. COST starts the heavy ones first.
  set(_cost 0)
  if("heavy" IN_LIST ARG_LABELS)
    set(_cost 100)
  endif()
  include(GoogleTest)
  gtest_discover_tests(${name}
    WORKING_DIRECTORY ${PROJECT_BINARY_DIR}
    PROPERTIES LABELS "${ARG_LABELS}" TIMEOUT ${ARG_TIMEOUT} COST ${_cost}
    DISCOVERY_TIMEOUT 60)
endfunction()

# roadslam_add_app(<exe-name> SOURCES ... DEPS ...)
function(roadslam_add_app name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS})
  roadslam_set_warnings(${name})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/bin)
  install(TARGETS ${name} RUNTIME DESTINATION bin)
endfunction()

# roadslam_add_bench(<name> SOURCES ... DEPS ...): a Google Benchmark program in build/bench/.
function(roadslam_add_bench name)
  if(NOT ROADSLAM_BUILD_BENCH)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} benchmark::benchmark)
  target_compile_definitions(${name} PRIVATE
    ROADSLAM_SHARED_DATA="${ROADSLAM_SHARED_DATA}"
    ROADSLAM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  roadslam_set_warnings(${name})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/bench)
endfunction()

# roadslam_add_fuzz(<name> SOURCES ... DEPS ...): a libFuzzer target (LLVMFuzzerTestOneInput) built only
# with -DROADSLAM_FUZZ=ON and clang. The same fuzz sources also go into a gtest driver with LABELS fuzz
# (fixed seed, bounded time) that CI runs with gcc.
function(roadslam_add_fuzz name)
  if(NOT ROADSLAM_FUZZ)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_compile_options(${name} PRIVATE -fsanitize=fuzzer,address,undefined)
  target_link_options(${name} PRIVATE -fsanitize=fuzzer,address,undefined)
  target_link_libraries(${name} PRIVATE ${ARG_DEPS})
endfunction()
