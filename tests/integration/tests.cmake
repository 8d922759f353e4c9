# Decks run through the vemcontact executable: vc_deck_test(name deck code regex [FILES ...] [ABSENT ...])
set(VC_DECKS "${CMAKE_CURRENT_LIST_DIR}/decks")
function(vc_deck_test name deck code regex)
  cmake_parse_arguments(A "" "" "FILES;ABSENT" ${ARGN})
  add_test(NAME deck_${name}
    COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:vemcontact> -DDECK=${deck}
            -DOUT=${CMAKE_CURRENT_BINARY_DIR}/deck-out/${name} -DCODE=${code} "-DREGEX=${regex}"
            "-DFILES=${A_FILES}" "-DABSENT=${A_ABSENT}"
            -P ${CMAKE_CURRENT_LIST_DIR}/run_deck.cmake)
  set_tests_properties(deck_${name} PROPERTIES LABELS deck)
endfunction()

# the example decks run and write their results
vc_deck_test(example1_cantilever "${PROJECT_SOURCE_DIR}/inputs/example1_cantilever.inp" 0 ""
  FILES example1_cantilever.pvd example1_cantilever_0001.vtu example1_cantilever.h5 example1_cantilever.log)
vc_deck_test(minimal_polygon ${VC_DECKS}/minimal_polygon.inp 0 "" FILES minimal_polygon_0001.vtu)

# the command line
add_test(NAME cli_help COMMAND vemcontact --help)
set_tests_properties(cli_help PROPERTIES PASS_REGULAR_EXPRESSION "usage: vemcontact")
add_test(NAME cli_version COMMAND vemcontact --version)
set_tests_properties(cli_version PROPERTIES PASS_REGULAR_EXPRESSION "vemcontact [0-9]+\\.[0-9]+")
add_test(NAME cli_unknown_option COMMAND vemcontact --frobnicate x.inp)
set_tests_properties(cli_unknown_option PROPERTIES WILL_FAIL TRUE)
# --blas-threads N|auto: auto or a whole number >= 1, else one clear message
add_test(NAME cli_blas_threads_bad COMMAND vemcontact --blas-threads 0 x.inp)
set_tests_properties(cli_blas_threads_bad PROPERTIES WILL_FAIL TRUE)
add_test(NAME cli_blas_threads_text COMMAND vemcontact --blas-threads two x.inp)
set_tests_properties(cli_blas_threads_text PROPERTIES
  PASS_REGULAR_EXPRESSION "--blas-threads takes auto or a whole number of at least 1, not \"two\"")
vc_deck_test(missing_deck ${VC_DECKS}/does_not_exist.inp 2 "does_not_exist.inp")

# bad input: exit status 1, one clear message naming file:line
vc_deck_test(err_clockwise ${VC_DECKS}/err_clockwise.inp 1 "err_clockwise.inp:[0-9]+: error: element 2 is clockwise")
vc_deck_test(err_zero_area ${VC_DECKS}/err_zero_area.inp 1 "err_zero_area.inp:[0-9]+: error: element 1 has zero area")
vc_deck_test(err_self_intersecting ${VC_DECKS}/err_self_intersecting.inp 1
  "err_self_intersecting.inp:[0-9]+: error: element 1 is self-intersecting")
vc_deck_test(err_repeated_node ${VC_DECKS}/err_repeated_node.inp 1 "element 1 uses node 2 twice")
vc_deck_test(err_several ${VC_DECKS}/err_several.inp 1 "element 1 is clockwise.*element 2 is self-intersecting")

# a model that cannot be solved: exit status 3, the floating part named; a run
# that fails in step 2 keeps step 1 on disk
vc_deck_test(floating_part ${VC_DECKS}/floating_part.inp 3 "part 2 of 2 .*element 2 .*floats: it can translate"
  ABSENT floating_part_0001.vtu)
vc_deck_test(fails_in_step2 ${VC_DECKS}/fails_in_step2.inp 3 "floats"
  FILES fails_in_step2_0001.vtu fails_in_step2.pvd fails_in_step2.h5 ABSENT fails_in_step2_0002.vtu)

# lengths outside 1e-130 .. 1e130: refused before any kernel can over- or underflow
vc_deck_test(err_coord_huge ${VC_DECKS}/err_coord_huge.inp 1
  "err_coord_huge.inp:[0-9]+: error: node 2 has a coordinate beyond 1e130")
vc_deck_test(err_coord_tiny ${VC_DECKS}/err_coord_tiny.inp 1
  "err_coord_tiny.inp:[0-9]+: error: element 1 is smaller than 1e-130")

# *SOLID SECTION, STABILIZATION=tau (VEM stabilisation factor): read and used (the
# tip deflection of paper example 1 falls as tau grows, tau = 1 is the default);
# refused on FEM elements and for values that are not positive numbers
add_test(NAME deck_stabilization_monotone
  COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:vemcontact> -DDECKS=${VC_DECKS}
          -DOUT=${CMAKE_CURRENT_BINARY_DIR}/deck-out/stabilization_monotone
          -P ${VC_DECKS}/stab_monotone.cmake)
set_tests_properties(deck_stabilization_monotone PROPERTIES LABELS deck)
vc_deck_test(err_stab_nonpositive ${VC_DECKS}/err_stab_nonpositive.inp 1
  "err_stab_nonpositive.inp:21: error: STABILIZATION = 0 must be positive.*err_stab_nonpositive.inp:23: error: STABILIZATION = -0.5 must be positive")
vc_deck_test(err_stab_text ${VC_DECKS}/err_stab_text.inp 1
  "err_stab_text.inp:17: error: parameter STABILIZATION of [*]SOLID SECTION must be a number, found 'soft'")
vc_deck_test(err_stab_fem ${VC_DECKS}/err_stab_fem.inp 1
  "err_stab_fem.inp:17: error: STABILIZATION= on FEM element 1")
vc_deck_test(err_stab_cpe4 ${VC_DECKS}/err_stab_cpe4.inp 1
  "err_stab_cpe4.inp:17: error: STABILIZATION= on FEM element 1")

# GENERATE ranges are checked before they are expanded (1..2147483647 took 20-60 s)
vc_deck_test(err_generate_huge ${VC_DECKS}/err_generate_huge.inp 1
  "err_generate_huge.inp:7: error: 2147483644 of the ids 1 to 2147483647 are not defined nodes [(]the first is 4[)]")

# input ranges: each value within 1e-130..1e130, estimated products within 1e-250..1e250,
# refused with file:line and the value (the Debug build trapped SIGFPE on these)
vc_deck_test(err_range_thickness ${VC_DECKS}/err_range_thickness.inp 1
  "err_range_thickness.inp:29: error: thickness of the section of BEAM = 1.00E[+]307 is beyond 1e-130 .. 1e130")
vc_deck_test(err_range_stabilization ${VC_DECKS}/err_range_stabilization.inp 1
  "err_range_stabilization.inp:29: error: STABILIZATION of the section of BEAM = 1.00E[+]307")
vc_deck_test(err_range_displacement ${VC_DECKS}/err_range_displacement.inp 1
  "err_range_displacement.inp [(]before the first [*]STEP[)]: error: prescribed displacement = 1.00E[+]307 at node 1")
vc_deck_test(err_range_density ${VC_DECKS}/err_range_density.inp 1
  "err_range_density.inp:26: error: density of material UNIT = 1.00E[+]307")
vc_deck_test(err_range_modulus ${VC_DECKS}/err_range_modulus.inp 1
  "err_range_modulus.inp:26: error: Young's modulus of material UNIT = 1.00E-307")
vc_deck_test(err_range_product ${VC_DECKS}/err_range_product.inp 1
  "err_range_product.inp:29: error: the displacement the loads make .* is about 1e270[)], beyond 1e-250 .. 1e250")

# A test that only says why it is skipped (a build without PETSc or without mpiexec):
# CTest reports it as skipped, not passed.
function(vc_skipped_test name why)
  add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} -E echo "skipped: ${why}")
  set_tests_properties(${name} PROPERTIES SKIP_REGULAR_EXPRESSION "skipped: ")
endfunction()

# The PETSc solvers (gamg, hypre, mumps) against CHOLMOD on a VEM cantilever, a
# polygon mesh, a Voronoi contact deck, an FEM contact deck and a contact deck whose
# iteration rebuilds the matrix pattern (--rebuilds: the solver analyses the new
# pattern), within tolerances derived from their stopping rules (compare_solvers.py);
# skipped, saying why, when CMake found no PETSc
if(VC_HAVE_PETSC)
  add_test(NAME petsc_solvers
    COMMAND "${VC_PYTHON}" "${CMAKE_CURRENT_LIST_DIR}/compare_solvers.py" --rebuilds sliding_rebuild
            $<TARGET_FILE:vemcontact>
            "${CMAKE_CURRENT_BINARY_DIR}/petsc-solvers"
            "${PROJECT_SOURCE_DIR}/inputs/example1_cantilever.inp" "${PROJECT_SOURCE_DIR}/inputs/block_selfweight.inp"
            "${PROJECT_SOURCE_DIR}/inputs/interface_voronoi_50.inp" "${PROJECT_SOURCE_DIR}/inputs/hertz_389_fem.inp"
            "${VC_DECKS}/sliding_rebuild.inp")
else()
  vc_skipped_test(petsc_solvers "vemcontact was built without PETSc (pkg-config PETSc not found; scripts/install-deps.sh installs petsc-dev)")
endif()
set_tests_properties(petsc_solvers PROPERTIES LABELS deck)
# the same under the MPI launcher with 2 processes (the mesh partitioned, each process
# assembling its elements, matrix and solves distributed, one set of result files), against
# the serial CHOLMOD answer: a body load, two contact decks and a cantilever with nonzero
# prescribed displacements and loads in two steps (the second without a new factorization),
# and a slider pushed along a track whose contact iteration rebuilds the matrix pattern
# (--rebuilds: every run must record a rebuild; the partition is kept across it), and
# non-matching VEM blocks bonded by a *TIE with an *EQUATION chain (each process
# eliminates the constraints from its share of the matrix);
# the partition recorded in the HDF5 file checked; skipped, saying why, without PETSc or mpiexec.
# Open MPI refuses root unless told (containers, CI run as root).
if(VC_HAVE_PETSC AND MPIEXEC_EXECUTABLE)
  add_test(NAME petsc_solvers_np2
    COMMAND "${VC_PYTHON}" "${CMAKE_CURRENT_LIST_DIR}/compare_solvers.py"
            --launcher "${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 2" --rebuilds sliding_rebuild
            $<TARGET_FILE:vemcontact>
            "${CMAKE_CURRENT_BINARY_DIR}/petsc-solvers-np2"
            "${PROJECT_SOURCE_DIR}/inputs/block_selfweight.inp" "${PROJECT_SOURCE_DIR}/inputs/interface_voronoi_50.inp"
            "${PROJECT_SOURCE_DIR}/inputs/hertz_389_fem.inp" "${VC_DECKS}/distributed_cantilever.inp"
            "${VC_DECKS}/sliding_rebuild.inp" "${VC_DECKS}/tie_equation.inp")
  set_tests_properties(petsc_solvers_np2 PROPERTIES
    ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1" PROCESSORS 2)
else()
  vc_skipped_test(petsc_solvers_np2 "needs PETSc and an MPI launcher (mpiexec not found or PETSc not built)")
endif()
set_tests_properties(petsc_solvers_np2 PROPERTIES LABELS deck)
# an error on one process (rank 0 finds the job locked) ends all of them, with its status
if(VC_HAVE_PETSC AND MPIEXEC_EXECUTABLE)
  add_test(NAME mpi_error_ends_all
    COMMAND "${VC_PYTHON}" "${CMAKE_CURRENT_LIST_DIR}/mpi_error_ends_all.py"
            "${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 2" $<TARGET_FILE:vemcontact>
            "${CMAKE_CURRENT_BINARY_DIR}/mpi-error-ends-all" "${PROJECT_SOURCE_DIR}/inputs/example1_cantilever.inp")
  set_tests_properties(mpi_error_ends_all PROPERTIES
    ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1" PROCESSORS 2 TIMEOUT 120)
  add_test(NAME mpi_model_error_once
    COMMAND "${VC_PYTHON}" "${CMAKE_CURRENT_LIST_DIR}/mpi_error_ends_all.py" --model-error
            "${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 2" $<TARGET_FILE:vemcontact>
            "${CMAKE_CURRENT_BINARY_DIR}/mpi-model-error-once" "${VC_DECKS}/floating_part.inp")
  set_tests_properties(mpi_model_error_once PROPERTIES
    ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1" PROCESSORS 2 TIMEOUT 120)
  add_test(NAME mpi_solver_error_once
    COMMAND "${VC_PYTHON}" "${CMAKE_CURRENT_LIST_DIR}/mpi_error_ends_all.py" --solver-error
            "${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 2" $<TARGET_FILE:vemcontact>
            "${CMAKE_CURRENT_BINARY_DIR}/mpi-solver-error-once" "${PROJECT_SOURCE_DIR}/inputs/example1_cantilever.inp")
  set_tests_properties(mpi_solver_error_once PROPERTIES
    ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1" PROCESSORS 2 TIMEOUT 120)
else()
  vc_skipped_test(mpi_error_ends_all "needs PETSc and an MPI launcher (mpiexec not found or PETSc not built)")
  vc_skipped_test(mpi_model_error_once "needs PETSc and an MPI launcher (mpiexec not found or PETSc not built)")
  vc_skipped_test(mpi_solver_error_once "needs PETSc and an MPI launcher (mpiexec not found or PETSc not built)")
endif()
set_tests_properties(mpi_error_ends_all mpi_model_error_once mpi_solver_error_once PROPERTIES LABELS deck)
# without PETSc, --solver gamg stops with a clear message, exit status 1
if(NOT VC_HAVE_PETSC)
  vc_deck_test(solver_gamg_without_petsc "${PROJECT_SOURCE_DIR}/inputs/example1_cantilever.inp" 1
    "built without PETSc")
endif()
# --solver auto (the default) stays CHOLMOD on a small deck (below auto_gamg_unknowns,
# src/solver/factory.f90): the solver that ran, read from the HDF5 root attribute
add_test(NAME auto_solver_small
  COMMAND "${VC_PYTHON}" "${CMAKE_CURRENT_LIST_DIR}/check_solver_attribute.py" $<TARGET_FILE:vemcontact>
          "${CMAKE_CURRENT_BINARY_DIR}/auto-solver-small" "${PROJECT_SOURCE_DIR}/inputs/example1_cantilever.inp" cholmod)
set_tests_properties(auto_solver_small PROPERTIES LABELS deck)
# auto's gamg that cannot converge (-ksp_max_it 2) falls back to CHOLMOD: the exact
# linear field of a 2e5-unknown bar and the HDF5 attribute naming cholmod
if(VC_HAVE_PETSC)
  add_test(NAME auto_solver_fallback
    COMMAND "${VC_PYTHON}" "${CMAKE_CURRENT_LIST_DIR}/solver_fallback.py" $<TARGET_FILE:vemcontact>
            "${CMAKE_CURRENT_BINARY_DIR}/auto-solver-fallback")
else()
  vc_skipped_test(auto_solver_fallback "vemcontact was built without PETSc (auto is cholmod)")
endif()
set_tests_properties(auto_solver_fallback PROPERTIES LABELS deck)
add_test(NAME cli_unknown_solver COMMAND vemcontact --solver frobnicate x.inp)
set_tests_properties(cli_unknown_solver PROPERTIES PASS_REGULAR_EXPRESSION "--solver takes auto, cholmod, gamg, hypre, mumps")

# *STATIC, SOLVER=: vemcontact's solvers chosen by the deck (the command line's --solver
# wins), CalculiX's names accepted for the default, anything else refused at its line
vc_deck_test(err_solver_unknown ${VC_DECKS}/err_solver_unknown.inp 1
  "err_solver_unknown.inp:[0-9]+: error: unknown SOLVER=FOO on \\*STATIC")
vc_deck_test(solver_calculix_name ${VC_DECKS}/solver_calculix_name.inp 0 "" FILES solver_calculix_name.h5)
if(VC_HAVE_PETSC)
  vc_deck_test(solver_mumps ${VC_DECKS}/solver_mumps.inp 0 "" FILES solver_mumps.h5)
else()
  vc_deck_test(solver_mumps ${VC_DECKS}/solver_mumps.inp 1 "built without PETSc")
endif()
# PETSc's own options reach it before it starts, under the launcher too (-log_view)
if(VC_HAVE_PETSC AND MPIEXEC_EXECUTABLE)
  add_test(NAME mpi_petsc_options
    COMMAND "${VC_PYTHON}" "${CMAKE_CURRENT_LIST_DIR}/mpi_petsc_options.py"
            "${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 2" $<TARGET_FILE:vemcontact>
            "${CMAKE_CURRENT_BINARY_DIR}/mpi-petsc-options" "${PROJECT_SOURCE_DIR}/inputs/example1_cantilever.inp")
  set_tests_properties(mpi_petsc_options PROPERTIES
    ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1" PROCESSORS 2 TIMEOUT 300)
else()
  vc_skipped_test(mpi_petsc_options "needs PETSc and an MPI launcher (mpiexec not found or PETSc not built)")
endif()
# the deck's SOLVER=CHOLMOD applies under the MPI launcher too, where it cannot run
if(VC_HAVE_PETSC AND MPIEXEC_EXECUTABLE)
  add_test(NAME deck_solver_cholmod_np2
    COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 2 $<TARGET_FILE:vemcontact> -q
            -o "${CMAKE_CURRENT_BINARY_DIR}/deck-out/solver_cholmod_np2" ${VC_DECKS}/solver_cholmod.inp)
  set_tests_properties(deck_solver_cholmod_np2 PROPERTIES
    ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1" PROCESSORS 2 LABELS deck
    PASS_REGULAR_EXPRESSION "SOLVER=CHOLMOD \\(\\*STATIC\\) runs on one process")
endif()

# SIGTERM and SIGINT at random points of a 20-step run keep the completed steps:
# exit 143/130, JOB.h5 with complete = 0, interrupted = the signal and the steps of
# a full run (docs/output-format.md, "Stopping a run"); the same under MPI
add_test(NAME interrupt_serial
  COMMAND "${VC_PYTHON}" "${CMAKE_CURRENT_LIST_DIR}/interrupt_run.py" $<TARGET_FILE:vemcontact>
          "${CMAKE_CURRENT_BINARY_DIR}/interrupt-serial" --trials 4)
set_tests_properties(interrupt_serial PROPERTIES LABELS deck TIMEOUT 300)
if(VC_HAVE_PETSC AND MPIEXEC_EXECUTABLE)
  add_test(NAME interrupt_mpi
    COMMAND "${VC_PYTHON}" "${CMAKE_CURRENT_LIST_DIR}/interrupt_run.py" $<TARGET_FILE:vemcontact>
            "${CMAKE_CURRENT_BINARY_DIR}/interrupt-mpi" --trials 3
            --mpi "${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 2")
  set_tests_properties(interrupt_mpi PROPERTIES
    ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1" PROCESSORS 2 TIMEOUT 300)
else()
  vc_skipped_test(interrupt_mpi "needs PETSc and an MPI launcher (mpiexec not found or PETSc not built)")
endif()
set_tests_properties(interrupt_mpi PROPERTIES LABELS deck)

# the bad-input corpus and numeric fuzz mutants (bench/corpus_runner.py), the small
# decks only: no signal, trap or backtrace, an exit status of the program (0..5)
add_test(NAME corpus_quick
  COMMAND "${VC_PYTHON}" "${PROJECT_SOURCE_DIR}/bench/corpus_runner.py" --exe $<TARGET_FILE:vemcontact>
          --quick --mutants 6 --keep "${CMAKE_CURRENT_BINARY_DIR}/corpus-quick")
set_tests_properties(corpus_quick PROPERTIES LABELS deck TIMEOUT 300)
