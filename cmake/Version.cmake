# Tallow's version as the source tree says at build time (stats.json's provenance): the project
# version and `git describe` of the checkout (commit, "-dirty" with uncommitted changes). A target
# that runs on every build regenerates generated/tallow_version.h, rewriting it only when the text
# changes, so that a new commit or a first edit shows up without recompiling anything else.
set(TALLOW_VERSION_HEADER "${CMAKE_BINARY_DIR}/generated/tallow_version.h")
add_custom_target(tallow_version ALL
  COMMAND "${CMAKE_COMMAND}" -DSOURCE_DIR=${CMAKE_SOURCE_DIR} -DOUTPUT=${TALLOW_VERSION_HEADER}
          -DPROJECT_VERSION=${PROJECT_VERSION} -P "${CMAKE_SOURCE_DIR}/cmake/version_script.cmake"
  BYPRODUCTS "${TALLOW_VERSION_HEADER}"
  VERBATIM)
