# Warnings on for every target of the project (not for third-party headers).
add_library(mdhd_warnings INTERFACE)
target_compile_options(mdhd_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow
  -Wnon-virtual-dtor -Wcast-align -Woverloaded-virtual -Wnull-dereference
  -Wimplicit-fallthrough)
if(MDHD_WERROR)
  target_compile_options(mdhd_warnings INTERFACE -Werror)
endif()
# GCC 12's -Wmaybe-uninitialized misfires on std::regex/std::function under ASan
# instrumentation; the optimised build keeps the warning.
if(MDHD_SANITIZE AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  target_compile_options(mdhd_warnings INTERFACE -Wno-maybe-uninitialized)
endif()
