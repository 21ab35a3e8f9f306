# Warnings on for every target of the project (not for third-party headers).
add_library(mdhd_warnings INTERFACE)
target_compile_options(mdhd_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow
  -Wnon-virtual-dtor -Wcast-align -Woverloaded-virtual -Wnull-dereference
  -Wimplicit-fallthrough)
if(MDHD_WERROR)
  target_compile_options(mdhd_warnings INTERFACE -Werror)
endif()
