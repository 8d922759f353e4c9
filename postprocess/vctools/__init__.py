"""vctools: pre- and post-processing for vemcontact (meshing, plots, regression comparison)
and its Python API (docs/python-api.md):

    import vctools
    res = vctools.run("inputs/dam_joint.inp", out="out/dam")   # run a deck, a Deck or deck text
    res = vctools.open("out/dam/dam_joint.h5")                 # read an existing run
    res.step("RESERVOIR")["U"]                                 # fields as numpy arrays

The API is imported on first use, so that the command-line tools (vc-mesh, ...)
do not load h5py when they do not need it.
"""

__version__ = "0.1.0"

_API = {"run", "open", "find_executable", "Result", "Step", "Mesh", "Table", "RunError", "ResultError"}


def __getattr__(name):
    if name in _API:
        from . import api
        return getattr(api, name)
    if name in ("Deck", "StepBuilder"):
        from . import deck
        return getattr(deck, name)
    raise AttributeError(f"module 'vctools' has no attribute {name!r}")


def __dir__():
    return sorted(list(globals()) + list(_API) + ["Deck", "StepBuilder"])
