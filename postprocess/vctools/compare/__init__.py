"""Regression comparison of vemcontact HDF5 results (vc-compare).

    from vctools.compare import read_results, compare
    report = compare(read_results("run.h5"), read_results("reference.h5"))
    report.ok, report.worst, report.problems

See docs/regression.md.
"""
from .core import ATOL_FACTOR, FIELDS, RTOL, Entry, Report, Tolerances, compare, compare_mesh
from .h5file import CompareError, Results, read_results

__all__ = ["ATOL_FACTOR", "FIELDS", "RTOL", "CompareError", "Entry", "Report", "Results", "Tolerances",
           "compare", "compare_mesh", "read_results"]
