# cmake -DMESSAGE=... -P missing.cmake: a test that fails saying what is missing.
message(FATAL_ERROR "${MESSAGE}")
