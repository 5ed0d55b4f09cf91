# Shaders are files under shaders/, embedded into the binary at build time (a generated .cpp of raw
# string literals) so that `tallow` runs from anywhere; --shader-dir overrides them for live editing.
# Call tallow_embed_shaders(target) from the folder that defines `target` (custom-command outputs
# belong to one directory scope). TALLOW_EXTRA_SHADER_FILES lists files from outside shaders/ as
# `name=path` (e.g. PNanoVDB.h from libnanovdb-dev): embedded under `name`, includable like the rest.
function(tallow_embed_shaders target)
  file(GLOB_RECURSE shader_files CONFIGURE_DEPENDS "${CMAKE_SOURCE_DIR}/shaders/*")
  set(output "${CMAKE_BINARY_DIR}/generated/embedded_shaders.cpp")
  set(extra_paths "")
  foreach(entry IN LISTS TALLOW_EXTRA_SHADER_FILES)
    string(REGEX REPLACE "^[^=]*=" "" path "${entry}")
    list(APPEND extra_paths "${path}")
  endforeach()
  # `;` would split the -D argument: the entries travel joined by `|`.
  string(REPLACE ";" "|" extra "${TALLOW_EXTRA_SHADER_FILES}")
  add_custom_command(
    OUTPUT "${output}"
    COMMAND "${CMAKE_COMMAND}" -DSHADER_ROOT=${CMAKE_SOURCE_DIR}/shaders -DOUTPUT=${output}
            "-DEXTRA=${extra}"
            -P "${CMAKE_SOURCE_DIR}/cmake/embed_shaders_script.cmake"
    DEPENDS ${shader_files} ${extra_paths} "${CMAKE_SOURCE_DIR}/cmake/embed_shaders_script.cmake"
    COMMENT "Embedding shaders"
    VERBATIM)
  target_sources(${target} PRIVATE "${output}")
endfunction()
