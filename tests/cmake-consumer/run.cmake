# Installs the built curvenet into WORK_DIR/prefix, then builds and runs the
# outside project in CONSUMER_SOURCE_DIR against it, as an embedder would.
include(${CMAKE_CURRENT_LIST_DIR}/outside_project.cmake)
file(REMOVE_RECURSE ${WORK_DIR})
curvenet_install(${CURVENET_BINARY_DIR} ${WORK_DIR}/prefix)
curvenet_build_outside(${CONSUMER_SOURCE_DIR} ${WORK_DIR}/build ${WORK_DIR}/prefix)
curvenet_run(output ${WORK_DIR}/build/consumer)
