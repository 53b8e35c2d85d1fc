"""HasseComplex: per-level data as NumPy columns, carried through edits."""
import numpy as np
import pytest

import starplex


def grid(n=4):
    pts = np.array([[x, y, 0] for y in range(n) for x in range(n)], dtype=float)
    tris = []
    for y in range(n - 1):
        for x in range(n - 1):
            a = y * n + x
            tris += [[a, a + 1, a + n + 1], [a, a + n + 1, a + n]]
    return pts, np.array(tris)


def test_columns_from_the_complex_and_set_data():
    pts, tris = grid()
    c = starplex.Complex(
        pts, tris, point_data={"h": pts[:, 0] * 10}, cell_data={"t": np.arange(len(tris))}
    )
    h = starplex.HasseComplex(c)
    assert h.f_vector() == [16, 33, 18]
    ids, verts = h.simplices(0)
    assert verts.shape == (16, 1)
    assert h.data(0)["h"].ravel().tolist() == (pts[verts[:, 0], 0] * 10).tolist()
    _, tv = h.simplices(2)
    # cell data lands on the triangle with the same vertices
    want = {tuple(sorted(t)): i for i, t in enumerate(tris.tolist())}
    assert h.data(2)["t"].ravel().tolist() == [want[tuple(t)] for t in tv.tolist()]
    assert h.has_data(2).all() and not h.has_data(1).any()
    _, ev = h.simplices(1)
    length = np.linalg.norm(pts[ev[:, 0]] - pts[ev[:, 1]], axis=1)
    h.set_data(1, "len", length)
    assert h.data(1)["len"].ravel().tolist() == length.tolist()
    with pytest.raises(ValueError, match="'bad'.*expected 33"):
        h.set_data(1, "bad", np.zeros(5))
    assert h.data(4) == {}  # a level above the complex's dimension: no columns
    with pytest.raises(ValueError, match="levels 0 to 11"):
        h.data(12)
    assert h.positions.tolist() == pts[verts[:, 0]].tolist()


def test_edits_carry_rows():
    pts, tris = grid()
    h = starplex.HasseComplex(starplex.Complex(pts, tris, point_data={"id": np.arange(16)}))
    _, ev = h.simplices(1)
    h.set_data(1, "e", np.arange(len(ev)))
    edge_value = {tuple(e): i for i, e in enumerate(ev.tolist())}
    kept = h.collapse([5, 6])  # interior edge
    assert kept in (5, 6) and h.f_vector() == [15, 30, 16]
    _, verts = h.simplices(0)
    assert sorted(h.data(0)["id"].ravel().tolist()) == sorted(set(range(16)) - {5, 6} | {kept})
    # surviving edges keep their values; merged ones keep the first's
    _, ev2 = h.simplices(1)
    vals = h.data(1)["e"].ravel().tolist()
    for e, v in zip(ev2.tolist(), vals):
        if 5 not in e and 6 not in e:
            assert v == edge_value[tuple(e)]
    assert h.positions[list(verts[:, 0]).index(kept)].tolist() == [1.5, 1.0, 0.0]
    p = h.split([0, 1])
    assert h.positions[list(h.simplices(0)[1][:, 0]).index(p)].tolist() == [0.5, 0.0, 0.0]
    assert not h.has_data(0)[list(h.simplices(0)[1][:, 0]).index(p)]
    assert np.isnan(h.data(1)["e"]).sum() == 0  # int column: missing rows read 0
    labels = h.simplices(0)[1][:, 0].tolist()
    before = h.positions
    h.smooth(0.5, 3)
    after = h.positions
    for v in (0, 3, 12, 15, 7, 11):  # boundary vertices stay
        assert after[labels.index(v)].tolist() == before[labels.index(v)].tolist()
    assert not np.array_equal(before, after)
    k = h.to_complex(labels=True)
    assert k.n_cells == h.f_vector()[2] and "id" in k.point_data and "label" in k.point_data
    assert k.info()["euler_characteristic"] == 1
    with pytest.raises(ValueError, match="not a simplex"):
        h.collapse([0, 15])
    with pytest.raises(ValueError):
        h.collapse([0, 1, 2])


def test_decimate_and_errors():
    pts, tris = grid(3)
    h = starplex.HasseComplex(starplex.Complex(pts, tris, point_data={"id": np.arange(9)}))
    p = h.decimate([3, 4])
    assert h.f_vector()[0] == 8
    labels = h.simplices(0)[1][:, 0].tolist()
    assert h.positions[labels.index(p)].tolist() == [0.5, 1.0, 0.0]
    assert h.data(0)["id"].ravel()[labels.index(p)] in (3, 4)
    h.positions = h.positions * 2
    assert h.positions[labels.index(p)].tolist() == [1.0, 2.0, 0.0]
    assert h.to_complex().points.max() == 4.0
    with pytest.raises(ValueError, match="positions"):
        h.positions = np.zeros((3, 3))
    with pytest.raises(ValueError, match="at most 3 coordinates"):
        starplex.HasseComplex(starplex.Complex(np.zeros((3, 4)), [[0, 1, 2]]))
    with pytest.raises(ValueError):
        starplex.HasseComplex(starplex.Complex(np.zeros((4, 3)), {"quad": [[0, 1, 2, 3]]}))


def test_levels_above_three():
    # two 4-simplices of 3D points sharing the tetrahedron 1-2-3-4 (a Rips-like complex: its
    # dimension is above its coordinates')
    pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1], [2, 2, 2]], float)
    cells = np.array([[0, 1, 2, 3, 4], [1, 2, 3, 4, 5]])
    c = starplex.Complex(pts, cells, cell_data={"w": [7.5, 8.5]})
    h = starplex.HasseComplex(c)
    assert h.f_vector() == [6, 14, 16, 9, 2]
    _, tv = h.simplices(4)
    assert sorted(zip(map(tuple, tv.tolist()), h.data(4)["w"].ravel().tolist())) == [
        ((0, 1, 2, 3, 4), 7.5),
        ((1, 2, 3, 4, 5), 8.5),
    ]
    _, tets = h.simplices(3)
    h.set_data(3, "n", np.arange(len(tets)))
    assert h.data(3)["n"].ravel().tolist() == list(range(9))
    # collapsing the edge 0-1 removes the 4-simplex that holds it: the other keeps its row
    kept = h.collapse([0, 1])
    assert h.f_vector() == [5, 10, 10, 5, 1]
    _, tv = h.simplices(4)
    assert tv.tolist() == [sorted([kept, 2, 3, 4, 5])]
    assert h.data(4)["w"].ravel().tolist() == [8.5]
    # a collapse creates no simplex: every tetrahedron left has a row (merged ones the first's)
    assert h.has_data(3).all()
    assert set(h.data(3)["n"].ravel().tolist()) <= set(range(9))
    back = h.to_complex()
    assert back.n_cells == 1
