# A hand edit of a generated table must fail the figures check: copies the
# documents into a scratch tree, changes one figure of the "builtins" table
# (the cheapest to compute), and expects `curvenet_figures --check` to exit 1
# naming the document and the command that rewrites the tables.
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR}/docs)
file(COPY ${SOURCE_DIR}/README.md DESTINATION ${WORK_DIR})
file(GLOB documents ${SOURCE_DIR}/docs/*.md)
file(COPY ${documents} DESTINATION ${WORK_DIR}/docs)

file(READ ${WORK_DIR}/README.md readme)
string(FIND "${readme}" "<!-- figures:builtins -->" start)
if(start LESS 0)
  message(FATAL_ERROR "README.md has no builtins table")
endif()
string(SUBSTRING "${readme}" ${start} -1 table)
# The first data row: `| `NAME` | FACES | ...`; its face count gains a digit.
string(REGEX MATCH "\n\\| `[^`]+` \\| [0-9]+ \\|" row "${table}")
if(row STREQUAL "")
  message(FATAL_ERROR "no data row in the builtins table")
endif()
string(REGEX REPLACE "([0-9]+) \\|$" "\\19 |" edited "${row}")
string(REPLACE "${row}" "${edited}" readme "${readme}")
file(WRITE ${WORK_DIR}/README.md "${readme}")

execute_process(COMMAND ${FIGURES} --check --only builtins --repo ${WORK_DIR}
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT result EQUAL 1)
  message(FATAL_ERROR "the edited table passed the check (exit ${result}):\n${output}")
endif()
if(NOT output MATCHES "README.md:[0-9]+: table \"builtins\" differs" OR NOT output MATCHES "figures.sh --update")
  message(FATAL_ERROR "the check failed without naming the table and the update command:\n${output}")
endif()
message(STATUS "hand edit detected:\n${output}")
