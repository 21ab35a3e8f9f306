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

# mdhd_tests(LABEL LIBS lib... [EXTRA_DEFINITIONS def...] [DEPENDS target...]):
# one GoogleTest executable per test_*.cpp in the current folder, named
# LABEL_test_x, labelled LABEL. Skipped while a library it needs is missing.
function(mdhd_tests label)
  cmake_parse_arguments(ARG "" "" "LIBS;EXTRA_DEFINITIONS;DEPENDS" ${ARGN})
  foreach(lib ${ARG_LIBS})
    if(NOT TARGET ${lib})
      return()  # the library is not there yet
    endif()
  endforeach()
  file(GLOB tests CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/test_*.cpp)
  foreach(src ${tests})
    get_filename_component(name ${src} NAME_WE)
    set(target ${label}_${name})
    add_executable(${target} ${src})
    target_link_libraries(${target} PRIVATE ${ARG_LIBS} GTest::gtest GTest::gtest_main
      GTest::gmock nlohmann_json::nlohmann_json mdhd_warnings)
    target_compile_definitions(${target} PRIVATE MDHD_SOURCE_DIR="${CMAKE_SOURCE_DIR}"
      MDHD_SHARED_DIR="${MDHD_SHARED_DIR}" ${ARG_EXTRA_DEFINITIONS})
    foreach(dep ${ARG_DEPENDS})
      add_dependencies(${target} ${dep})
    endforeach()
    gtest_discover_tests(${target} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS ${label})
  endforeach()
endfunction()
