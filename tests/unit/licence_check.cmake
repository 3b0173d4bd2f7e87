# The licence state that README's Licence section states, checked on the built files:
#   BINARY     an executable; the GPL libraries among what it loads at run time (its NEEDED
#              entries, readelf -d, and everything they load in turn, ldd) must be exactly
#              GPL_EXPECTED (names without ".so.N"; empty: none), so that a new one and one that
#              has gone both fail until README says so;
#   CERES_FREE static libraries that must not reference Ceres or CHOLMOD (nm -u).
# Run as: cmake -DBINARY=... -DGPL_EXPECTED="a;b" -DCERES_FREE="x.a;y.a" -P licence_check.cmake
cmake_minimum_required(VERSION 3.20)

# GPL-licensed libraries a Debian build could pull in: SuiteSparse's GPL modules (through Ceres)
# and common GPL-only libraries.
set(gpl_libraries libcholmod libspqr libumfpack librbio libgsl libfftw3 libreadline)

find_program(READELF readelf REQUIRED)
find_program(LDD ldd REQUIRED)
find_program(NM nm REQUIRED)

execute_process(COMMAND "${READELF}" -d "${BINARY}" OUTPUT_VARIABLE dynamic RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "readelf -d ${BINARY} failed (${status})")
endif()
execute_process(COMMAND "${LDD}" "${BINARY}" OUTPUT_VARIABLE closure RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "ldd ${BINARY} failed (${status})")
endif()
string(REGEX MATCHALL "Shared library: \\[[^].]+" needed "${dynamic}")
string(REGEX MATCHALL "(^|\n)[ \t]*[^ \t\n.]+" loaded "${closure}")
set(found "")
foreach(entry IN LISTS needed loaded)
  string(REGEX REPLACE "^(Shared library: \\[|[ \t\n]+)" "" name "${entry}")
  if(name IN_LIST gpl_libraries AND NOT name IN_LIST found)
    list(APPEND found "${name}")
  endif()
endforeach()
list(SORT found)
set(expected "${GPL_EXPECTED}")
list(SORT expected)
if(NOT "${found}" STREQUAL "${expected}")
  message(FATAL_ERROR "${BINARY} needs the GPL libraries [${found}], README's Licence section "
                      "says [${expected}]: remove the dependency or update README and this test")
endif()
message(STATUS "${BINARY}: GPL libraries needed [${found}], as README states")

foreach(archive IN LISTS CERES_FREE)
  execute_process(COMMAND "${NM}" -C -u "${archive}" OUTPUT_VARIABLE symbols RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "nm -u ${archive} failed (${status})")
  endif()
  string(REGEX MATCH "[^\n]*(ceres::|cholmod_)[^\n]*" hit "${symbols}")
  if(hit)
    message(FATAL_ERROR "${archive} references Ceres or CHOLMOD (${hit}); it is meant to link neither")
  endif()
endforeach()
message(STATUS "no Ceres or CHOLMOD reference in: ${CERES_FREE}")
