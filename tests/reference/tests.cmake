# Regression tests: every deck under inputs/ runs through the (Debug) executable
# and its HDF5 result is compared with tests/reference/<deck>.h5 by vc-compare
# (python -m vctools.compare, default tolerances: docs/regression.md).  A deck
# without a reference fails with the command that makes one.  Label: regress
# (every deck runs in well under a second; a long deck would get the label slow
# as well, by adding its name to VC_REGRESS_SLOW).
# Include from tests/CMakeLists.txt after unit/output/tests.cmake (VC_PYTHON).
if(NOT DEFINED VC_PYTHON)
  set(VC_PYTHON "${PROJECT_SOURCE_DIR}/.venv/bin/python" CACHE FILEPATH "Python with numpy and h5py")
endif()
set(VC_REGRESS_SLOW "" CACHE STRING "decks (names without .inp) whose regress test is also labelled slow")
file(GLOB VC_REGRESS_DECKS CONFIGURE_DEPENDS "${PROJECT_SOURCE_DIR}/inputs/*.inp")
foreach(deck IN LISTS VC_REGRESS_DECKS)
  get_filename_component(job "${deck}" NAME_WLE)
  add_test(NAME regress_${job}
    COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:vemcontact> "-DDECK=${deck}"
            "-DREF=${CMAKE_CURRENT_LIST_DIR}/${job}.h5" "-DOUT=${CMAKE_CURRENT_BINARY_DIR}/regress-out/${job}"
            "-DPYTHON=${VC_PYTHON}" "-DPYTHONPATH=${PROJECT_SOURCE_DIR}/postprocess"
            -P "${CMAKE_CURRENT_LIST_DIR}/run_regress.cmake")
  set(labels regress)
  if(job IN_LIST VC_REGRESS_SLOW)
    list(APPEND labels slow)
  endif()
  set_tests_properties(regress_${job} PROPERTIES LABELS "${labels}")
endforeach()

# The stored references themselves pass the physics checks (Hertz peak, interface
# pressure, cantilever tip, dam, block equilibrium): README.md in this folder.
add_test(NAME regress_reference_checks
  COMMAND "${VC_PYTHON}" "${CMAKE_CURRENT_LIST_DIR}/check.py" "${CMAKE_CURRENT_LIST_DIR}")
set_tests_properties(regress_reference_checks PROPERTIES LABELS regress)
