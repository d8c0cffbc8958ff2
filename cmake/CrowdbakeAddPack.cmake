# crowdbake_add_pack: cook a character into a .crowdpack as a build step of a game's
# own CMake project.
#
#   include(CrowdbakeAddPack)   # after list(APPEND CMAKE_MODULE_PATH <crowdbake>/cmake)
#   crowdbake_add_pack(<target>
#     INPUT  <character .glb/.gltf/.fbx>
#     OUTPUT <pack .crowdpack>
#     [CONFIG <bake config .json>]      # docs/bake-config.md
#     [CROWDBAKE <path or target of the crowdbake executable>]  # default: ${CROWDBAKE_EXECUTABLE}
#     [ALL])                             # build it with the default target
#
# The bake writes a depfile, so the pack is rebuilt when the character, any external
# buffer or texture it references, the config, or its pose-range file changes; the
# output is written atomically, so an interrupted build never leaves a broken pack.
cmake_policy(PUSH)
cmake_policy(SET CMP0116 NEW)  # depfile paths are made relative to the build tree

function(crowdbake_add_pack target)
  cmake_parse_arguments(PACK "ALL" "INPUT;OUTPUT;CONFIG;CROWDBAKE" "" ${ARGN})
  if(NOT PACK_INPUT OR NOT PACK_OUTPUT)
    message(FATAL_ERROR "crowdbake_add_pack(${target}): INPUT and OUTPUT are required")
  endif()
  if(NOT PACK_CROWDBAKE)
    set(PACK_CROWDBAKE ${CROWDBAKE_EXECUTABLE})
  endif()
  if(NOT PACK_CROWDBAKE)
    message(FATAL_ERROR "crowdbake_add_pack(${target}): pass CROWDBAKE or set CROWDBAKE_EXECUTABLE")
  endif()
  get_filename_component(input ${PACK_INPUT} ABSOLUTE BASE_DIR ${CMAKE_CURRENT_SOURCE_DIR})
  get_filename_component(output ${PACK_OUTPUT} ABSOLUTE BASE_DIR ${CMAKE_CURRENT_BINARY_DIR})
  set(command ${PACK_CROWDBAKE} bake ${input} -o ${output} --depfile ${output}.d --quiet)
  set(depends ${input})
  if(PACK_CONFIG)
    get_filename_component(config ${PACK_CONFIG} ABSOLUTE BASE_DIR ${CMAKE_CURRENT_SOURCE_DIR})
    list(APPEND command --config ${config})
    list(APPEND depends ${config})
  endif()
  if(TARGET ${PACK_CROWDBAKE})
    list(APPEND depends ${PACK_CROWDBAKE})
  endif()
  add_custom_command(OUTPUT ${output}
                     COMMAND ${command}
                     DEPENDS ${depends}
                     DEPFILE ${output}.d
                     COMMENT "Baking ${PACK_OUTPUT}"
                     VERBATIM)
  if(PACK_ALL)
    add_custom_target(${target} ALL DEPENDS ${output})
  else()
    add_custom_target(${target} DEPENDS ${output})
  endif()
endfunction()

cmake_policy(POP)
