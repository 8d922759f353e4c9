"""The mesher's spatial numbering (vctools.mesh.mesh.spatial_order): the Hilbert key
is a curve through neighbouring grid cells, the renumbered mesh has the same cells,
sets, surfaces and joint records, and a cell's nodes end up close in number."""
import copy

import numpy as np

from vctools.mesh.mesh import hilbert_key, spatial_order
from vctools.mesh.polymesh import Joint, VBody, voronoi_group


def test_hilbert_key_walks_through_neighbours():
    g = np.array([(i, j) for i in range(16) for j in range(16)], float)
    k = hilbert_key(g, bits=4)
    assert sorted(k) == list(range(256))           # one key per grid cell
    steps = np.abs(np.diff(g[np.argsort(k)], axis=0)).sum(1)
    assert np.all(steps == 1)                       # each step to an edge neighbour


def cells_by_coords(m):
    return {tuple(map(tuple, m.nodes[m.cell(i)])): i for i in range(m.ncell)}


def test_same_mesh_renumbered_locally():
    poly = [[0, 0], [2, 0], [2, 1], [0, 1]]
    m0 = voronoi_group([VBody("B", poly, 2000)], [Joint("J", [[0.3, 0.5], [1.7, 0.55]])], seed=3, lloyd=5)
    m = spatial_order(copy.deepcopy(m0))
    # the same nodes and the same cells with their corners in the same (counter-clockwise) order
    assert sorted(map(tuple, m.nodes)) == sorted(map(tuple, m0.nodes))
    old, new = cells_by_coords(m0), cells_by_coords(m)
    assert old.keys() == new.keys()
    cmap = np.empty(m.ncell, np.int64)
    for key, i in old.items():
        cmap[i] = new[key]
    assert np.array_equal(m.cell_body[cmap], m0.cell_body)
    # sets, surfaces and the joint's records name the same points and cells
    for name in m0.nsets:
        assert np.array_equal(m.nodes[m.nsets[name]], m0.nodes[m0.nsets[name]])
    for name in m0.nsurfaces:
        assert np.array_equal(m.nodes[m.nsurfaces[name]], m0.nodes[m0.nsurfaces[name]])
    for name in m0.elsets:
        assert np.array_equal(m.elsets[name], cmap[m0.elsets[name]])
    for name, (c0, s0) in m0.esurfaces.items():
        c, s = m.esurfaces[name]
        assert np.array_equal(c, cmap[c0]) and np.array_equal(s, s0)
    j0, j = m0.info["joints"][0], m.info["joints"][0]
    assert np.array_equal(m.nodes[j["shared"]], m0.nodes[j0["shared"]])
    assert np.array_equal(m.nodes[j["slave"]], m0.nodes[j0["slave"]])
    assert np.array_equal(j["master"][0], cmap[j0["master"][0]])
    assert ({tuple(m.nodes[k]): sorted(map(tuple, m.nodes[v])) for k, v in j["copies"].items()}
            == {tuple(m0.nodes[k]): sorted(map(tuple, m0.nodes[v])) for k, v in j0["copies"].items()})

    # locality: the spread of node numbers within a cell.  The mesher numbers in
    # the random order of its seeds (median spread a sizeable fraction of the
    # nodes); along the curve a cell's nodes are neighbours on it, so the median
    # spread is a few cells' worth of nodes (bound: 2 % of the nodes)
    def median_spread(mm):
        return np.median([np.ptp(mm.cell(i)) for i in range(mm.ncell)])
    assert median_spread(m) < 0.02 * len(m.nodes) < median_spread(m0)
