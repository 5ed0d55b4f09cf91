# glad is generated at configure time from Debian's python3-glad; --reproducible uses the Khronos
# XML bundled with the package, so no network is needed.
find_program(GLAD_EXECUTABLE glad REQUIRED)
set(GLAD_OUT "${CMAKE_BINARY_DIR}/glad")
set(GLAD_ARGS --quiet --api gl:core=4.5
    --extensions GL_KHR_debug,GL_NVX_gpu_memory_info,GL_ATI_meminfo,GL_ARB_shader_viewport_layer_array,GL_ARB_pipeline_statistics_query
    --reproducible --out-path "${GLAD_OUT}" c)
if(NOT EXISTS "${GLAD_OUT}/src/gl.c" OR NOT "${GLAD_ARGS}" STREQUAL "${TALLOW_GLAD_ARGS_USED}")
  execute_process(COMMAND "${GLAD_EXECUTABLE}" ${GLAD_ARGS} RESULT_VARIABLE glad_rc ERROR_VARIABLE glad_err)
  if(NOT glad_rc EQUAL 0)
    message(FATAL_ERROR "glad generation failed: ${glad_err}")
  endif()
  set(TALLOW_GLAD_ARGS_USED "${GLAD_ARGS}" CACHE INTERNAL "")
endif()
add_library(tallow_glad STATIC "${GLAD_OUT}/src/gl.c")
target_include_directories(tallow_glad SYSTEM PUBLIC "${GLAD_OUT}/include")
target_link_libraries(tallow_glad PUBLIC ${CMAKE_DL_LIBS})
