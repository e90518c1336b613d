# curvenet_write_version_script(OUTPUT HEADER...) — the linker version script
# of the shared library: the C interface (curvenet_*) and every class and
# namespace-level function that the installed headers declare in
# curvenet::v1, and nothing else. The engine's internal classes and helpers
# (patches, ribbons, plans, kernels, parallel loops) share the v1 namespace
# but are declared only under src/, so they stay local to the library.
#
# Declarations are taken from lines that start in column 0 inside the
# headers' namespace, as STYLE.md lays them out: `struct NAME`, `class NAME`
# and `TYPE NAME(` for functions.
function(curvenet_write_version_script output)
  set(classes)
  set(functions)
  foreach(header IN LISTS ARGN)
    # Split into lines by hand: a CMake list would join lines across the
    # brackets and semicolons of C++ code.
    file(READ ${header} content)
    string(REGEX REPLACE "[][;]" " " content "${content}")
    string(REPLACE "\n" ";" lines "${content}")
    foreach(line IN LISTS lines)
      if(line MATCHES "^(struct|class) ([A-Za-z_][A-Za-z0-9_]*)")
        list(APPEND classes ${CMAKE_MATCH_2})
      elseif(line MATCHES "^[A-Za-z][^=(]*[ *&]([a-z][A-Za-z0-9_]*)\\(")
        list(APPEND functions ${CMAKE_MATCH_1})
      endif()
    endforeach()
  endforeach()
  list(REMOVE_DUPLICATES classes)
  list(REMOVE_DUPLICATES functions)
  list(SORT classes)
  list(SORT functions)
  set(script "/* Generated from the installed headers by cmake/public_symbols.cmake. */\nCURVENET_${PROJECT_VERSION_MAJOR} {\n  global:\n    curvenet_*;\n    extern \"C++\" {\n")
  foreach(name IN LISTS classes)
    # Members, but not the private implementation a class may keep in a
    # nested Impl (Model::Impl, Surface::Impl): a `local:` pattern cannot
    # take back what a global wildcard matched, so the globals skip "Im".
    string(APPEND script "      curvenet::v1::${name}::[!I]*;\n"
                         "      curvenet::v1::${name}::I[!m]*;\n"
                         "      \"typeinfo for curvenet::v1::${name}\";\n"
                         "      \"typeinfo name for curvenet::v1::${name}\";\n"
                         "      \"vtable for curvenet::v1::${name}\";\n")
  endforeach()
  foreach(name IN LISTS functions)
    # The version-script lexer takes no parentheses: NAME* is the closest
    # pattern to "NAME(any arguments)" (tests/shared-library checks that no
    # longer internal name slips through it).
    string(APPEND script "      curvenet::v1::${name}*;\n")
  endforeach()
  string(APPEND script "    };\n  local:\n    *;\n};\n")
  file(CONFIGURE OUTPUT ${output} CONTENT "${script}" @ONLY)
endfunction()
