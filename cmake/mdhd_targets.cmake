# The two shapes every folder of the project takes.

# mdhd_library(NAME [DEPENDS lib...]): a static library of every *.cpp in the
# current folder, include paths from the repository root. Libraries of the engine
# depend one way: gcode <- kinematics <- geometry <- mdh <- mesh, check.
function(mdhd_library name)
  cmake_parse_arguments(ARG "" "" "DEPENDS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  if(NOT sources)
    return()  # nothing to build here yet
  endif()
  add_library(${name} STATIC ${sources})
  target_include_directories(${name} PUBLIC ${CMAKE_SOURCE_DIR})
  target_link_libraries(${name} PUBLIC glm::glm Threads::Threads PRIVATE mdhd_warnings)
  foreach(dep ${ARG_DEPENDS})
    target_link_libraries(${name} PUBLIC ${dep})
  endforeach()
endfunction()

# mdhd_tests(LABEL LIBS lib... [EXTRA_DEFINITIONS def...] [DEPENDS target...] [NO_UNITY]):
# one GoogleTest executable LABEL_tests of every test_*.cpp in the current folder,
# each test labelled LABEL and run by ctest as its own process (Suite.Name, so
# `ctest -R` finds it as before). Skipped while a library it needs is missing.
#
# Why one executable per folder, built as one unity translation unit: the cost of
# a test file is mostly not its own code but what it instantiates from gtest,
# nlohmann json and httplib, compiled again (at -O2, or under ASan) in every file.
# Merged, a folder pays that once: the release test objects went from 319 to 173
# CPU seconds (80 files -> 11 executables; README "CI time"). The price: the
# anonymous namespaces of a folder's files share one scope, so two files may not
# define the same helper name (the compiler says so: fold the helper into the
# folder's shared header, or give it a name of its file). NO_UNITY keeps a
# folder's files apart (tests/mdh, until its helpers have their own names).
function(mdhd_tests label)
  cmake_parse_arguments(ARG "NO_UNITY" "" "LIBS;EXTRA_DEFINITIONS;DEPENDS" ${ARGN})
  foreach(lib ${ARG_LIBS})
    if(NOT TARGET ${lib})
      return()  # the library is not there yet
    endif()
  endforeach()
  file(GLOB tests CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/test_*.cpp)
  if(NOT tests)
    return()
  endif()
  set(target ${label}_tests)
  add_executable(${target} ${tests})
  target_link_libraries(${target} PRIVATE ${ARG_LIBS} GTest::gtest GTest::gtest_main
    GTest::gmock nlohmann_json::nlohmann_json mdhd_warnings)
  target_compile_definitions(${target} PRIVATE MDHD_SOURCE_DIR="${CMAKE_SOURCE_DIR}"
    MDHD_SHARED_DIR="${MDHD_SHARED_DIR}" ${ARG_EXTRA_DEFINITIONS})
  if(NOT ARG_NO_UNITY)
    # Batch 0: the whole folder in one translation unit (2 cores, 11 folders).
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 0)
    if(MDHD_SANITIZE)
      # Under ASan + UBSan the test code itself at -O0: -O1 doubled the compile
      # time of these unity files (ASan test objects 323 -> 175 CPU s), same test
      # run time; the code under test, the libraries, stays at -O1 and the
      # instrumentation is the same. Not for tests/mdh: its files are small, and
      # its brute-force reference model ran 2.5x slower at -O0.
      target_compile_options(${target} PRIVATE -O0)
    endif()
  endif()
  foreach(dep ${ARG_DEPENDS})
    add_dependencies(${target} ${dep})
  endforeach()
  # NO_PRETTY_VALUES: a parameter's printed value (a pointer, padding bytes) would make
  # ctest's test names change from build to build; the instantiations name their cases.
  gtest_discover_tests(${target} DISCOVERY_TIMEOUT 60 NO_PRETTY_VALUES PROPERTIES LABELS ${label})
endfunction()
