# Runs GENERATOR [INPUT] OUT and fails unless OUT is byte for byte EXPECTED (a file the project
# generated and checked in must be what its generator writes today).
execute_process(COMMAND "${GENERATOR}" ${INPUT} "${OUT}" RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${GENERATOR} failed (${status})")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${OUT}" "${EXPECTED}" RESULT_VARIABLE differ)
if(NOT differ EQUAL 0)
  message(FATAL_ERROR "${EXPECTED} differs from what ${GENERATOR} writes (${OUT}); regenerate it")
endif()
