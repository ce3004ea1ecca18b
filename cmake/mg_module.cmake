# Helpers shared by every module: a library with its alias, a thin program, a GoogleTest suite.

function(mg_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wshadow)
  # GCC 12 reports OpenMesh's and CGAL's deliberately uninitialised vectors (VectorT(),
  # Point_3()) as maybe-uninitialised inside our code once inlined: false positives we
  # cannot fix in system headers.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE -Wno-maybe-uninitialized)
  endif()
  if(MG_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  # And one rule of arithmetic: a * b + c is never fused into one rounding. G restores its
  # cones by the expressions make_cone uses, inline in other translation units
  # (garbing/primitives.h), and counts on the same roundings there; with FMA instructions
  # (-march=native, aarch64) GCC would otherwise fuse where it sees fit.
  target_compile_options(${target} PRIVATE -ffp-contract=off)
endfunction()

# mg_add_library(<target> ALIAS <name> SOURCES ... [PUBLIC ...] [PRIVATE ...])
# Creates the static library <target>, its alias mg::<name>, include dir <module>/include, and
# installs both into the CMake package (export set garbingTargets, exported as mg::<name>; see
# cmake/garbingConfig.cmake.in).
function(mg_add_library target)
  cmake_parse_arguments(A "" "ALIAS" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  add_library(${target} STATIC ${A_SOURCES})
  add_library(mg::${A_ALIAS} ALIAS ${target})
  # Position-independent: the Python module (python/) links them into a shared object.
  # With GCC, -fno-semantic-interposition keeps inlining as without -fPIC (our symbols are never
  # interposed).
  set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE -fno-semantic-interposition)
  endif()
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
                                              $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${target} PUBLIC ${A_PUBLIC} PRIVATE ${A_PRIVATE})
  target_compile_features(${target} PUBLIC cxx_std_17)  # the headers use C++17, for users too
  mg_set_warnings(${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${A_ALIAS})
  install(TARGETS ${target} EXPORT garbingTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

# mg_add_program(<name> SOURCES ... LIBS ...): an executable landing in <build>/bin/, installed
# into <prefix>/bin.
function(mg_add_program name)
  cmake_parse_arguments(A "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${A_SOURCES})
  target_link_libraries(${name} PRIVATE ${A_LIBS})
  mg_set_warnings(${name})
  install(TARGETS ${name} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()

# mg_add_gtest(<name> SOURCES ... LIBS ... [PROPERTIES ...]): a GoogleTest executable whose
# tests CTest discovers one by one. PROPERTIES go to every discovered test (fixtures, labels);
# without them the tests are labelled `unit` (self-contained: what the sanitizer job runs).
function(mg_add_gtest name)
  cmake_parse_arguments(A "" "" "SOURCES;LIBS;PROPERTIES" ${ARGN})
  add_executable(${name} ${A_SOURCES})
  target_link_libraries(${name} PRIVATE ${A_LIBS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    MG_SOURCE_DIR="${PROJECT_SOURCE_DIR}" MG_BINARY_DIR="${PROJECT_BINARY_DIR}")
  mg_set_warnings(${name})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests)
  if(A_PROPERTIES)
    gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES ${A_PROPERTIES})
  else()
    gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS unit)
    add_dependencies(unit_tests ${name})
  endif()
endfunction()

# mg_add_benchmark(<name> SOURCES ... LIBS ...): a Google Benchmark program in <build>/bench/
# (not a test: benchmarks measure, tests assert).
function(mg_add_benchmark name)
  cmake_parse_arguments(A "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${A_SOURCES})
  target_link_libraries(${name} PRIVATE ${A_LIBS} mg::bench_support)
  mg_set_warnings(${name})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/bench)
endfunction()

# mg_add_python_test(<name> SCRIPT <file> [ARGS ...]): a Python test script of this folder, run
# by CTest with Debian's interpreter (program-level checks: exit codes, messages, no partial
# output). Properties (fixtures, labels) go through set_tests_properties.
function(mg_add_python_test name)
  cmake_parse_arguments(A "" "SCRIPT" "ARGS" ${ARGN})
  add_test(NAME ${name}
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/${A_SCRIPT} ${A_ARGS})
endfunction()

# mg_add_fuzz_target(<name> SOURCES ... SEEDS <folder> LIBS ...) (MG_FUZZ, clang): a libFuzzer
# program in <build>/fuzz/, and a CTest entry (label `fuzz`) running it for MG_FUZZ_RUNS inputs
# from the seeds in <folder> (relative to this module) through core/fuzz/run_fuzz.cmake: a
# fresh <build>/fuzz/corpus/<name>/ each run, findings in <build>/fuzz/artifacts/<name>/.
# Long runs: docs/testing.md.
function(mg_add_fuzz_target name)
  cmake_parse_arguments(A "" "SEEDS" "SOURCES;LIBS" ${ARGN})
  set(fuzz_dir ${PROJECT_BINARY_DIR}/fuzz)
  add_executable(${name} ${A_SOURCES})
  target_link_libraries(${name} PRIVATE ${A_LIBS})
  target_link_options(${name} PRIVATE -fsanitize=fuzzer)
  mg_set_warnings(${name})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${fuzz_dir})
  add_test(NAME ${name}
    COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:${name}> -DCORPUS=${fuzz_dir}/corpus/${name}
            -DSEEDS=${CMAKE_CURRENT_SOURCE_DIR}/${A_SEEDS} -DRUNS=${MG_FUZZ_RUNS}
            -DARTIFACTS=${fuzz_dir}/artifacts/${name}
            -P ${PROJECT_SOURCE_DIR}/core/fuzz/run_fuzz.cmake)
  set_tests_properties(${name} PROPERTIES LABELS fuzz)
endfunction()
