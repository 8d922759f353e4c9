"""Reproduction of Sun et al. (2022), "The virtual element method for the dam
foundation with joint": runs the paper's four examples and writes
paper-reproduction.md with its tables and figures regenerated
(``python -m vctools.paper --help``, ``vc-paper``).  ``reproduce`` holds the runs,
numbers and figures, ``document`` the text (it imports ``reproduce``, never the
reverse), ``cli`` the command.  ``vctools.paper.runs`` reads our result
files (contact CSV, log, HDF5) for the curve tools."""
