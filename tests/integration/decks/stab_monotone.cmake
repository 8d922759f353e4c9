# STABILIZATION= reaches the element: paper example 1 (2d/b = 1) with tau = 0.5,
# 1 and 2 and without the parameter.  The tip deflection (the run's max |u_y|,
# both tip nodes have the same exact value 0.3) must fall strictly as tau grows:
# tau scales the only stiffness that holds the bending (hourglass) mode of the
# two elements; and STABILIZATION=1 must print exactly the default's deflection.
#   cmake -DEXE=... -DDECKS=<this folder> -DOUT=... -P stab_monotone.cmake
file(REMOVE_RECURSE "${OUT}")
foreach(job default tau1 tau0p5 tau2)
  execute_process(COMMAND "${EXE}" -o "${OUT}" "${DECKS}/stab_ex1_${job}.inp"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "stab_ex1_${job}: exit status ${rc}\n${out}${err}")
  endif()
  if(NOT out MATCHES "max \\|u_y\\| +([0-9.E+-]+)")
    message(FATAL_ERROR "stab_ex1_${job}: no 'max |u_y|' in the output\n${out}")
  endif()
  set(uy_${job} "${CMAKE_MATCH_1}")
  # E-notation to a plain decimal for the comparisons below (CMake math is integer)
  string(REGEX MATCH "^([0-9])\\.([0-9]+)E([+-][0-9]+)$" m "${CMAKE_MATCH_1}")
  if(NOT m OR NOT CMAKE_MATCH_3 STREQUAL "-02")
    message(FATAL_ERROR "stab_ex1_${job}: deflection ${uy_${job}} not of order 1e-2 (expected 0.02..0.09)")
  endif()
  set(key_${job} "${CMAKE_MATCH_1}${CMAKE_MATCH_2}")
  message(STATUS "stab_ex1_${job}: max |u_y| = ${uy_${job}}")
endforeach()
if(NOT uy_tau1 STREQUAL uy_default)
  message(FATAL_ERROR "STABILIZATION=1 gives ${uy_tau1}, the default ${uy_default}: must be identical")
endif()
if(NOT (key_tau0p5 GREATER key_tau1 AND key_tau1 GREATER key_tau2))
  message(FATAL_ERROR "tip deflection not decreasing in tau: tau=0.5 ${uy_tau0p5}, 1 ${uy_tau1}, 2 ${uy_tau2}")
endif()
message(STATUS "ok: decreasing in tau")
