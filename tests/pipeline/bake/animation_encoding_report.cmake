# Animation encoding measurements behind docs/animation-encoding.md. Not a unit test: run by
# hand (build/tests/pipeline/animation_encoding_report [--keep-root-motion] [--fps N]).
add_executable(animation_encoding_report ${CMAKE_CURRENT_LIST_DIR}/animation_encoding_report.cpp)
target_link_libraries(animation_encoding_report PRIVATE crowdbake_pipeline crowdbake_spectator
                      crowdbake_warnings nlohmann_json::nlohmann_json)
target_compile_definitions(animation_encoding_report PRIVATE
                           CROWDBAKE_SHARED_ASSETS="${CROWDBAKE_SHARED_ASSETS}")
# The on-disk codings (lossless zstd, error-bounded) are formats internals; the report measures them
# directly, as formats/bench does.
target_include_directories(animation_encoding_report PRIVATE ${PROJECT_SOURCE_DIR}/formats/src)
