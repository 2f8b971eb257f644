# Compiles GLSL compute shaders to SPIR-V at build time and embeds the words in a C++ source,
# so binaries need no shader files at run time.
#   strata_add_shaders(TARGET name SOURCES a.comp b.comp INCLUDE_DIRS dir...)
# creates a static library `name` exposing strata::shaders::spirv("a") -> std::span<const uint32_t>.
# Each source listed in TEXTURED is compiled a second time with STRATA_TEXTURES defined, as "a_textured"
# (the textured variant: include/scene_bridge.glsl).
function(strata_add_shaders)
  cmake_parse_arguments(S "" "TARGET" "SOURCES;INCLUDE_DIRS;DEPENDS;TEXTURED" ${ARGN})
  set(include_flags)
  foreach(dir ${S_INCLUDE_DIRS})
    list(APPEND include_flags "-I${dir}")
  endforeach()
  set(spv_files)
  set(names)
  set(builds)
  foreach(src ${S_SOURCES})
    list(APPEND builds "${src}|")
  endforeach()
  foreach(src ${S_TEXTURED})
    list(APPEND builds "${src}|_textured")
  endforeach()
  foreach(build ${builds})
    string(REPLACE "|" ";" parts "${build}")
    list(GET parts 0 src)
    list(LENGTH parts n)
    set(suffix "")
    set(defines)
    if(n GREATER 1)
      list(GET parts 1 suffix)
    endif()
    if(suffix STREQUAL "_textured")
      set(defines -DSTRATA_TEXTURES=1)
    endif()
    get_filename_component(name ${src} NAME_WE)
    set(name ${name}${suffix})
    set(spv ${CMAKE_CURRENT_BINARY_DIR}/spv/${name}.spv)
    set(dep ${CMAKE_CURRENT_BINARY_DIR}/spv/${name}.d)
    add_custom_command(
      OUTPUT ${spv}
      COMMAND ${CMAKE_COMMAND} -E make_directory ${CMAKE_CURRENT_BINARY_DIR}/spv
      COMMAND ${GLSLANG_VALIDATOR} --quiet --target-env vulkan1.3 -g0 ${include_flags} ${defines}
              --depfile ${dep} -o ${spv} ${CMAKE_CURRENT_SOURCE_DIR}/${src}
      DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${src} ${S_DEPENDS}
      DEPFILE ${dep}
      COMMENT "glslang ${name}"
      VERBATIM)
    list(APPEND spv_files ${spv})
    list(APPEND names ${name})
  endforeach()
  set(out_cpp ${CMAKE_CURRENT_BINARY_DIR}/${S_TARGET}_embedded.cpp)
  add_custom_command(
    OUTPUT ${out_cpp}
    COMMAND ${CMAKE_COMMAND} -DOUT=${out_cpp} "-DNAMES=${names}" "-DFILES=${spv_files}"
            -P ${PROJECT_SOURCE_DIR}/cmake/EmbedSpirv.cmake
    DEPENDS ${spv_files} ${PROJECT_SOURCE_DIR}/cmake/EmbedSpirv.cmake
    COMMENT "embedding SPIR-V into ${S_TARGET}"
    VERBATIM)
  add_library(${S_TARGET} STATIC ${out_cpp})
  target_include_directories(${S_TARGET} PUBLIC ${PROJECT_SOURCE_DIR}/shaders)
endfunction()
