# Helpers for the outside-project tests (cmake -P scripts): install the built
# curvenet into a scratch prefix, then configure, build and run a project
# that knows curvenet only through find_package, as an embedder would.

function(curvenet_install binary_dir prefix)
  execute_process(COMMAND ${CMAKE_COMMAND} --install ${binary_dir} --prefix ${prefix} RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "install failed: ${rc}")
  endif()
endfunction()

function(curvenet_build_outside source_dir build_dir prefix)
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${source_dir} -B ${build_dir} -G ${CMAKE_GENERATOR}
                          -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release
                  RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "configure of ${source_dir} failed: ${rc}")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${build_dir} RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "build of ${source_dir} failed: ${rc}")
  endif()
endfunction()

# Runs a program; its standard output goes to the variable named `out_var`.
function(curvenet_run out_var)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "${ARGN}:\n${out}${err}")
  if(rc)
    message(FATAL_ERROR "${ARGV1} failed: ${rc}")
  endif()
  set(${out_var} "${out}" PARENT_SCOPE)
endfunction()
