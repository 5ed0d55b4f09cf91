# Shaders are files under shaders/, embedded into the binary at build time (a generated .cpp of raw
# string literals) so that `tallow` runs from anywhere; --shader-dir overrides them for live editing.
# Call tallow_embed_shaders(target) from the folder that defines `target` (custom-command outputs
# belong to one directory scope).
function(tallow_embed_shaders target)
  file(GLOB_RECURSE shader_files CONFIGURE_DEPENDS "${CMAKE_SOURCE_DIR}/shaders/*")
  set(output "${CMAKE_BINARY_DIR}/generated/embedded_shaders.cpp")
  add_custom_command(
    OUTPUT "${output}"
    COMMAND "${CMAKE_COMMAND}" -DSHADER_ROOT=${CMAKE_SOURCE_DIR}/shaders -DOUTPUT=${output}
            -P "${CMAKE_SOURCE_DIR}/cmake/embed_shaders_script.cmake"
    DEPENDS ${shader_files} "${CMAKE_SOURCE_DIR}/cmake/embed_shaders_script.cmake"
    COMMENT "Embedding shaders"
    VERBATIM)
  target_sources(${target} PRIVATE "${output}")
endfunction()
