"""Reading the contact iteration records that vemcontact writes into JOB.h5
(/steps/NNNN/contact/iterations, docs/output-format.md), for the tests."""
import h5py
import numpy as np


def iteration_records(h5_path):
    """Per step with contact iterations (in step order): a dict of the record arrays
    (iteration, active, changed, residual, max_penetration, max_pressure, step,
    factorized, rebuilt, time)."""
    out = []
    with h5py.File(h5_path, "r") as f:
        for key in sorted(f["steps"]):
            g = f["steps"][key].get("contact/iterations")
            if g is not None:
                out.append({name: np.array(g[name]) for name in g})
    return out


def contact_iterations(h5_path):
    """The number of contact iterations of every step with contact."""
    return [int(r["iteration"].size) for r in iteration_records(h5_path)]


def line_search_steps(h5_path):
    """The line search step of every iteration of every step, in order."""
    return [float(s) for r in iteration_records(h5_path) for s in r["step"]]


def factorizations(h5_path):
    """The number of numeric factorizations of every step with contact."""
    return [int(r["factorized"].sum()) for r in iteration_records(h5_path)]


def pattern_rebuilds(h5_path):
    """The number of matrix pattern rebuilds of every step with contact."""
    return [int(r["rebuilt"].sum()) for r in iteration_records(h5_path)]


def assert_rf_balanced(h5_path, rtol=1e-8):
    """RF_total balances LOAD_total in every step (docs/output-format.md: RF is the
    support's force, contact included): |RF_total + LOAD_total| <= rtol (sum |RF| +
    |LOAD_total|); 1e-8: the contact iterations converge to a residual of 1e-10 of the
    forces, and the sum over the nodes adds the round-off of K u."""
    with h5py.File(h5_path, "r") as f:
        for key in sorted(f["steps"]):
            g = f["steps"][key]
            if "RF_total" not in g or "LOAD_total" not in g:
                continue
            rf, load = np.array(g["RF_total"]), np.array(g["LOAD_total"])
            scale = np.abs(np.array(g["RF"])).sum() + np.abs(load).sum()
            # nothing loaded or supported (an open contact, no load): RF is round-off
            # of K u alone, with no force to measure it against
            if not np.any(load) and scale < 1e-10:
                continue
            assert np.abs(rf + load).max() <= rtol * scale, (h5_path, key, rf, load)


def increment_iterations(h5_path):
    """The contact iterations of every increment that the file holds records of, per
    step in step order: the frames' (/increments/NNNN/MMMM/contact/iterations, written
    with FREQUENCY=n) in increment order, then the step's end (/steps/NNNN, its last
    increment)."""
    out = []
    with h5py.File(h5_path, "r") as f:
        for key in sorted(f["steps"]):
            counts = []
            frames = f.get(f"increments/{key}")
            for m in sorted(frames) if frames is not None else []:
                g = frames[m].get("contact/iterations")
                if g is not None:
                    counts.append(int(np.array(g["iteration"]).size))
            g = f["steps"][key].get("contact/iterations")
            if g is not None:
                counts.append(int(np.array(g["iteration"]).size))
            out.append(counts)
    return out
