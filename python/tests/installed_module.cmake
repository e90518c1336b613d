# The installed module (cmake -P script): `cmake --install --prefix P` puts
# curvenet.<abi>.so and curvenet.pyi into P/MODULE_DIR, and the interpreter
# imports the module from there (not from the build tree) and works.
# Inputs: CURVENET_BINARY_DIR, WORK_DIR, PYTHON, MODULE_DIR.
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
execute_process(COMMAND ${CMAKE_COMMAND} --install ${CURVENET_BINARY_DIR} --prefix ${prefix}
                OUTPUT_VARIABLE log RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "install failed: ${rc}")
endif()
if(NOT log MATCHES "The Python module curvenet is in ${prefix}/${MODULE_DIR}")
  message(FATAL_ERROR "the install did not say where the module went:\n${log}")
endif()
if(NOT EXISTS ${prefix}/${MODULE_DIR}/curvenet.pyi)
  message(FATAL_ERROR "no curvenet.pyi in ${prefix}/${MODULE_DIR}")
endif()
set(ENV{PYTHONPATH} ${prefix}/${MODULE_DIR})
execute_process(COMMAND ${PYTHON} -c
  "import curvenet, pathlib; print(pathlib.Path(curvenet.__file__).parent); m = curvenet.Model.load('builtin:pentagon'); print(m.tessellate(resolution=4).triangles.shape)"
  WORKING_DIRECTORY ${WORK_DIR} OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "the installed module does not import:\n${err}")
endif()
if(NOT out MATCHES "^${prefix}/${MODULE_DIR}\n\\(80, 3\\)")
  message(FATAL_ERROR "imported from elsewhere or wrong mesh:\n${out}")
endif()
message(STATUS "${out}")
