# The shared library as an outside user meets it (cmake -P script):
#  1. installed into a scratch prefix, libcurvenet.so.MAJOR carries its
#     SONAME (objdump -p);
#  2. its dynamic symbol table (nm -D --defined-only) holds the C interface
#     of curvenet.h, all of it, and C++ symbols of curvenet::v1 whose
#     top-level name an installed header declares, and nothing else: no
#     kernels, no private Impl, no library code of TBB, Highway or the
#     standard library;
#  3. a C program built with `pkg-config --cflags --libs curvenet` alone
#     and a C++ example built with the same line (plus -std=c++20) run.
# Inputs: CURVENET_BINARY_DIR, SOURCE_DIR (the repository), WORK_DIR, MAJOR.
cmake_policy(VERSION 3.22)
include(${SOURCE_DIR}/tests/cmake-consumer/outside_project.cmake)
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
curvenet_install(${CURVENET_BINARY_DIR} ${prefix})
file(GLOB library ${prefix}/lib*/libcurvenet.so.${MAJOR} ${prefix}/lib*/*/libcurvenet.so.${MAJOR})
if(NOT library)
  message(FATAL_ERROR "no libcurvenet.so.${MAJOR} under ${prefix}")
endif()
get_filename_component(libdir ${library} DIRECTORY)

# 1. SONAME.
execute_process(COMMAND objdump -p ${library} OUTPUT_VARIABLE dynamic RESULT_VARIABLE rc)
if(rc OR NOT dynamic MATCHES "SONAME +libcurvenet\\.so\\.${MAJOR}\n")
  message(FATAL_ERROR "objdump -p ${library}: no SONAME libcurvenet.so.${MAJOR}")
endif()

# 2. Exported symbols.
execute_process(COMMAND nm -D --defined-only -C ${library} OUTPUT_VARIABLE symbols RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "nm -D failed on ${library}")
endif()
file(GLOB headers ${prefix}/include/curvenet/*)
set(declarations "")
foreach(header IN LISTS headers)
  file(READ ${header} text)
  string(APPEND declarations "${text}")
endforeach()
file(READ ${prefix}/include/curvenet/curvenet.h c_header)
string(REGEX MATCHALL "curvenet_[a-z0-9_]+\\(" c_functions "${c_header}")
list(TRANSFORM c_functions REPLACE "\\($" "")
list(REMOVE_DUPLICATES c_functions)

string(REGEX REPLACE "[][;]" " " symbols "${symbols}")
string(REPLACE "\n" ";" lines "${symbols}")
set(count 0)
set(exported_c "")
set(wrong "")
foreach(line IN LISTS lines)
  if(NOT line MATCHES "^[0-9a-f]+ [A-Za-z] (.*)$")
    continue()
  endif()
  string(REGEX REPLACE "@@?CURVENET_[0-9]+$" "" symbol "${CMAKE_MATCH_1}")
  if(symbol MATCHES "^CURVENET_[0-9]+$") # the version node of the version script
    continue()
  endif()
  math(EXPR count "${count} + 1")
  if(symbol MATCHES "^curvenet_[a-z0-9_]+$")
    list(APPEND exported_c ${symbol})
    continue()
  endif()
  if(symbol MATCHES "::Impl::" OR NOT symbol MATCHES "^(typeinfo for |typeinfo name for |vtable for )?curvenet::v1::([A-Za-z_][A-Za-z0-9_]*)")
    list(APPEND wrong "${symbol}")
    continue()
  endif()
  # The top-level name must be declared in an installed header, as a type
  # or a function of that name (not only as part of a longer identifier).
  set(name ${CMAKE_MATCH_2})
  if(NOT declarations MATCHES "[^A-Za-z0-9_]${name}[ (]")
    list(APPEND wrong "${symbol}")
  endif()
endforeach()
if(wrong)
  list(JOIN wrong "\n  " listed)
  message(FATAL_ERROR "libcurvenet.so exports symbols outside the public API:\n  ${listed}")
endif()
foreach(function IN LISTS c_functions)
  if(NOT function IN_LIST exported_c)
    message(FATAL_ERROR "curvenet.h declares ${function}, libcurvenet.so does not export it")
  endif()
endforeach()
list(LENGTH c_functions c_count)
message(STATUS "libcurvenet.so.${MAJOR}: ${count} exported symbols, ${c_count} C functions, all public")

# 3. pkg-config alone.
set(ENV{PKG_CONFIG_PATH} ${libdir}/pkgconfig)
set(ENV{LD_LIBRARY_PATH} ${libdir})
execute_process(COMMAND pkg-config --cflags --libs curvenet OUTPUT_VARIABLE flags RESULT_VARIABLE rc
                OUTPUT_STRIP_TRAILING_WHITESPACE)
if(rc)
  message(FATAL_ERROR "pkg-config does not find curvenet under ${libdir}/pkgconfig")
endif()
separate_arguments(flags UNIX_COMMAND "${flags}")
execute_process(COMMAND cc -o ${WORK_DIR}/c_program ${SOURCE_DIR}/tests/shared-library/main.c ${flags}
                RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "cc main.c $(pkg-config --cflags --libs curvenet) failed")
endif()
curvenet_run(output ${WORK_DIR}/c_program)
execute_process(COMMAND c++ -std=c++20 -O1 -o ${WORK_DIR}/cpp_program ${SOURCE_DIR}/examples/pentagon-cpp/main.cpp
                        ${flags} RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "c++ -std=c++20 pentagon-cpp/main.cpp $(pkg-config --cflags --libs curvenet) failed")
endif()
curvenet_run(output ${WORK_DIR}/cpp_program ${WORK_DIR}/pentagon.obj 4)
execute_process(COMMAND ldd ${WORK_DIR}/cpp_program OUTPUT_VARIABLE linked)
if(NOT linked MATCHES "libcurvenet\\.so\\.${MAJOR} => ${libdir}")
  message(FATAL_ERROR "the C++ program does not use the installed libcurvenet.so.${MAJOR}:\n${linked}")
endif()
