# Embeds the JSON Schemas in mdh_protocol as string literals, so the binary can
# validate and serve them without its source tree. Re-runs when a schema changes.
file(READ ${CMAKE_CURRENT_LIST_DIR}/job.schema.json MDHD_JOB_SCHEMA)
file(READ ${CMAKE_CURRENT_LIST_DIR}/report.schema.json MDHD_REPORT_SCHEMA)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
  ${CMAKE_CURRENT_LIST_DIR}/job.schema.json ${CMAKE_CURRENT_LIST_DIR}/report.schema.json)
configure_file(${CMAKE_CURRENT_LIST_DIR}/schema_texts.cpp.in
  ${CMAKE_CURRENT_BINARY_DIR}/generated/schema_texts.cpp @ONLY)
target_sources(mdh_protocol PRIVATE ${CMAKE_CURRENT_BINARY_DIR}/generated/schema_texts.cpp)
