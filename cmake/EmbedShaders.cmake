# Shaders are files under shaders/, embedded into the binary at build time (a generated .cpp of raw
# string literals) so that `tallow` runs from anywhere; --shader-dir overrides them for live editing.
file(GLOB_RECURSE TALLOW_SHADER_FILES CONFIGURE_DEPENDS
     RELATIVE "${CMAKE_SOURCE_DIR}/shaders" "${CMAKE_SOURCE_DIR}/shaders/*")
set(TALLOW_EMBEDDED_SHADERS_CPP "${CMAKE_BINARY_DIR}/generated/embedded_shaders.cpp")
set(_shader_deps "")
foreach(f IN LISTS TALLOW_SHADER_FILES)
  list(APPEND _shader_deps "${CMAKE_SOURCE_DIR}/shaders/${f}")
endforeach()
add_custom_command(
  OUTPUT "${TALLOW_EMBEDDED_SHADERS_CPP}"
  COMMAND "${CMAKE_COMMAND}" -DSHADER_ROOT=${CMAKE_SOURCE_DIR}/shaders
          -DOUTPUT=${TALLOW_EMBEDDED_SHADERS_CPP} -P "${CMAKE_SOURCE_DIR}/cmake/embed_shaders_script.cmake"
  DEPENDS ${_shader_deps} "${CMAKE_SOURCE_DIR}/cmake/embed_shaders_script.cmake"
  COMMENT "Embedding shaders"
  VERBATIM)
