# Builds the three programs of examples/ as outside projects against the
# installed package, runs them, and checks that the C++ and the C program
# write the mesh the tessellation contract promises: one 5-sided face at
# resolution r has 5 corner vertices, 5 (r − 1) edge samples and
# 1 + 5 (r − 1) + 5 (r − 1)(r − 2) / 2 interior vertices, and 5 r² triangles.
include(${CMAKE_CURRENT_LIST_DIR}/outside_project.cmake)
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
curvenet_install(${CURVENET_BINARY_DIR} ${prefix})

set(r 16)
math(EXPR expected_vertices "5 + 5 * (${r} - 1) + 1 + 5 * (${r} - 1) + 5 * (${r} - 1) * (${r} - 2) / 2")
math(EXPR expected_triangles "5 * ${r} * ${r}")

foreach(example IN ITEMS pentagon-cpp pentagon-c)
  curvenet_build_outside(${EXAMPLES_DIR}/${example} ${WORK_DIR}/${example} ${prefix})
  set(obj ${WORK_DIR}/${example}.obj)
  curvenet_run(output ${WORK_DIR}/${example}/${example} ${obj} ${r})
  file(STRINGS ${obj} vertices REGEX "^v ")
  file(STRINGS ${obj} triangles REGEX "^f ")
  list(LENGTH vertices nv)
  list(LENGTH triangles nt)
  if(NOT nv EQUAL expected_vertices OR NOT nt EQUAL expected_triangles)
    message(FATAL_ERROR "${example}: ${nv} vertices, ${nt} triangles; expected ${expected_vertices}, ${expected_triangles}")
  endif()
  # Both programs build the same curves with the same scheme.
  string(REGEX MATCH "centre \\([^)]*\\)" centre_${example} "${output}")
endforeach()
if(NOT centre_pentagon-cpp STREQUAL centre_pentagon-c)
  message(FATAL_ERROR "the C and C++ programs disagree: ${centre_pentagon-cpp} vs ${centre_pentagon-c}")
endif()

# The batch program on a small batch (the full 10⁶ points is its default).
curvenet_build_outside(${EXAMPLES_DIR}/batch-evaluate ${WORK_DIR}/batch-evaluate ${prefix})
curvenet_run(output ${WORK_DIR}/batch-evaluate/batch-evaluate 20000)
if(NOT output MATCHES "points/s")
  message(FATAL_ERROR "batch-evaluate printed no rate")
endif()
