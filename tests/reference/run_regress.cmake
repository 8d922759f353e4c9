# Run one deck and compare its HDF5 result with the reference (tests.cmake).
#   cmake -DEXE=... -DDECK=... -DREF=... -DOUT=... -DPYTHON=... -DPYTHONPATH=... -P run_regress.cmake
get_filename_component(job "${DECK}" NAME_WLE)
if(NOT EXISTS "${REF}")
  message(FATAL_ERROR "no reference ${REF} for ${DECK}: make it with\n"
          "  bash tests/reference/regenerate.sh inputs/${job}.inp\n"
          "and record how it was checked in tests/reference/README.md")
endif()
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${EXE}" -q -o "${OUT}" "${DECK}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "vemcontact ${DECK}: exit status ${rc}\n${out}${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E env "PYTHONPATH=${PYTHONPATH}"
                "${PYTHON}" -m vctools.compare "${OUT}/${job}.h5" "${REF}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${job}: the result differs from ${REF} (vc-compare exit status ${rc})")
endif()
