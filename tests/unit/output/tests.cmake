# Output checks run with Python: check_vtu.py reads the .vtu files that
# test_output_vtu writes (next to its executable; zlib-compressed and raw) with
# meshio and compares every array exactly;
# check_hdf5.py reads test_output_hdf5's file with h5py to confirm the layout
# (shapes as Python sees them, dtypes, attributes) that docs/output-format.md
# documents.  They fail when the interpreter or the packages are missing: the
# venv is part of the test setup (postprocess/ requirements), not optional.
# Include from tests/CMakeLists.txt after the unit-test loop (it adds fixture
# properties to the Fortran tests defined there).
set(VC_PYTHON "${PROJECT_SOURCE_DIR}/.venv/bin/python" CACHE FILEPATH
  "Python with numpy, meshio and h5py, used by the output tests")

add_test(NAME test_output_vtu_meshio
  COMMAND "${VC_PYTHON}" "${CMAKE_CURRENT_LIST_DIR}/check_vtu.py"
          "$<TARGET_FILE_DIR:test_output_vtu>/test_output_vtu.vtu"
          "$<TARGET_FILE_DIR:test_output_vtu>/test_output_vtu_raw.vtu"
          "$<TARGET_FILE_DIR:test_output_vtu>/test_output_vtu_extra.vtu"
          "$<TARGET_FILE_DIR:test_output_vtu>/test_output_vtu.expected")
set_tests_properties(test_output_vtu PROPERTIES FIXTURES_SETUP vc_output_vtu_file)
set_tests_properties(test_output_vtu_meshio PROPERTIES
  FIXTURES_REQUIRED vc_output_vtu_file LABELS unit)

add_test(NAME test_output_hdf5_h5py
  COMMAND "${VC_PYTHON}" "${CMAKE_CURRENT_LIST_DIR}/check_hdf5.py"
          "$<TARGET_FILE_DIR:test_output_hdf5>/test_output_hdf5.h5")
set_tests_properties(test_output_hdf5 PROPERTIES FIXTURES_SETUP vc_output_hdf5_file)
set_tests_properties(test_output_hdf5_h5py PROPERTIES
  FIXTURES_REQUIRED vc_output_hdf5_file LABELS unit)
