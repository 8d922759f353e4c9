"""Reproduction of Sun et al. (2022), "The virtual element method for the dam
foundation with joint": runs the paper's four examples and writes
docs/paper-reproduction.md with its tables and figures regenerated
(``python -m vctools.paper --help``).  ``vctools.paper.runs`` reads our result
files (contact CSV, log, HDF5) for the curve tools."""
