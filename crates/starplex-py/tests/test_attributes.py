"""Attributes as NumPy columns: constructor, setters, files, conversions."""
import importlib.util
import os
import pathlib
import warnings

import numpy as np
import pytest

import starplex
from conftest import SMALL, need_data


def square():
    pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], dtype=float)
    return pts, np.array([[0, 1, 2], [1, 3, 2]])


def test_constructor_getters_and_dtypes():
    pts, tris = square()
    c = starplex.Complex(
        pts,
        tris,
        point_data={"h": np.array([0.5, 1.5, 2.5, 3.5]), "rgb": np.arange(12).reshape(4, 3)},
        cell_data={"tag": np.array([7, 9], dtype=np.uint8), "on": [True, False]},
    )
    pd, cd = c.point_data, c.cell_data
    assert list(pd) == ["h", "rgb"] and list(cd) == ["tag", "on"]
    assert pd["h"].shape == (4, 1) and pd["h"].dtype == np.float64
    assert pd["rgb"].shape == (4, 3) and pd["rgb"].dtype == np.int64
    assert pd["rgb"].tolist() == np.arange(12).reshape(4, 3).tolist()
    assert cd["tag"].dtype == np.int64 and cd["tag"].ravel().tolist() == [7, 9]
    assert cd["on"].ravel().tolist() == [1, 0]
    # NaN is data, not an error
    c2 = starplex.Complex(pts, tris, point_data={"f": [np.nan, 0, 1, 2]})
    assert np.isnan(c2.point_data["f"][0, 0])
    info = c.info()["attributes"]
    assert [a["name"] for a in info["vertex"]] == ["h", "rgb"]
    assert info["cell"][0] == {"name": "tag", "type": "int", "components": 1, "min": 7.0, "max": 9.0}


def test_setters_replace_and_check():
    pts, tris = square()
    c = starplex.Complex(pts, tris)
    assert c.point_data == {} and c.cell_data == {}
    c.point_data = {"id": np.arange(4)}
    c.cell_data = {"w": np.array([[0.5, 1.0], [2.0, 3.0]])}
    assert c.point_data["id"].ravel().tolist() == [0, 1, 2, 3]
    assert c.cell_data["w"].shape == (2, 2)
    with pytest.raises(ValueError, match="'bad'"):
        c.point_data = {"bad": np.arange(5)}
    assert list(c.point_data) == ["id"]  # unchanged
    with pytest.raises(ValueError, match="'t'.*expected 2"):
        c.cell_data = {"t": [1, 2, 3]}
    with pytest.raises(ValueError, match="'t'"):
        starplex.Complex(pts, tris, cell_data={"t": [1]})
    with pytest.raises(TypeError, match=r"point_data\['s'\].*dtype"):
        c.point_data = {"s": np.array(["a", "b", "c", "d"])}
    with pytest.raises(TypeError, match="dict"):
        c.point_data = [1, 2, 3, 4]
    with pytest.raises(ValueError, match="shape"):
        c.point_data = {"x": np.zeros((4, 2, 2))}
    with pytest.raises(ValueError, match="int64"):
        c.point_data = {"x": np.full(4, 2**63, dtype=np.uint64)}
    c.point_data = None
    c.cell_data = {}
    assert c.point_data == {} and c.cell_data == {}
    # structures built before keep working
    s = starplex.IaStar(c)
    c.point_data = {"id": np.arange(4)}
    assert s.vt(1).tolist() == [0, 1]


def test_dropped_cells_take_their_rows():
    pts, _ = square()
    cells = {"tri": [[0, 1, 2], [1, 3, 2], [2, 1, 0]], "line": [[0, 1]]}
    c = starplex.Complex(
        pts, cells, drop_duplicates=True, drop_faces=True, cell_data={"t": [10, 11, 12, 13]}
    )
    assert c.n_cells == 2
    assert c.cell_data["t"].ravel().tolist() == [10, 11]


def test_write_read_round_trip_and_warning(tmp_path):
    pts, tris = square()
    c = starplex.Complex(
        pts, tris, point_data={"h": [0.0, 1.0, 2.0, 3.0]}, cell_data={"tag": [[1, 2], [3, 4]]}
    )
    for ext in ("vtu", "vtk"):
        p = tmp_path / f"m.{ext}"
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            c.write(p)
        r = starplex.read(p)
        assert r.point_data["h"].ravel().tolist() == [0.0, 1.0, 2.0, 3.0]
        assert r.cell_data["tag"].tolist() == [[1, 2], [3, 4]]
    with pytest.warns(UserWarning, match="vertex h, cell tag.*not written"):
        c.write(tmp_path / "m.off")
    assert starplex.read(tmp_path / "m.off").point_data == {}


def test_attributes_read_from_files():
    need_data()
    data = pathlib.Path(os.environ.get("STARPLEX_DATA", "/nonexistent")) / "small"
    found = [
        m
        for name, p, _ in SMALL
        for m in (p.with_suffix(".msh"), data / name / f"{name}.msh")
        if m.is_file()
    ]
    if not found:
        pytest.skip("SKIPPED: no small dataset with a .msh file")
    p = found[0]
    c = starplex.read(p, drop_duplicates=True)
    cd = c.cell_data
    tags = [n for n in cd if n in ("gmsh:physical", "gmsh:geometrical")]
    assert tags and all(cd[n].shape == (c.n_cells, 1) and cd[n].dtype == np.int64 for n in tags)
    if importlib.util.find_spec("meshio"):
        import meshio

        m = meshio.read(p)
        for n in tags:
            ours = set(np.unique(cd[n]).tolist())
            theirs = set(np.unique(np.concatenate(m.cell_data[n])).tolist())
            assert ours and ours <= theirs
    medit = p.with_suffix(".mesh")
    if medit.is_file():
        k = starplex.read(medit, drop_duplicates=True)
        assert "medit:ref" in k.cell_data


def test_meshio_and_trimesh_carry_attributes():
    pts, tris = square()
    c = starplex.Complex(pts, tris, point_data={"h": [0.0, 1.0, 2.0, 3.0]}, cell_data={"t": [5, 6]})
    if importlib.util.find_spec("trimesh"):
        t = starplex.to_trimesh(c)
        assert t.vertex_attributes["h"].tolist() == [0.0, 1.0, 2.0, 3.0]
        assert t.face_attributes["t"].tolist() == [5, 6]
    if not importlib.util.find_spec("meshio"):
        pytest.skip("SKIPPED: meshio not installed (to_meshio)")
    mixed = starplex.Complex(
        np.zeros((6, 3)),
        {"quad": [[0, 1, 2, 3]], "tri": [[2, 3, 4]], "line": [[4, 5]]},
        cell_data={"t": [1, 2, 3]},
        point_data={"v": np.arange(12.0).reshape(6, 2)},
    )
    m = starplex.to_meshio(mixed)
    assert [b.type for b in m.cells] == ["quad", "triangle", "line"]
    assert [a.tolist() for a in m.cell_data["t"]] == [[1], [2], [3]]
    back = starplex.from_meshio(m)
    assert back.cell_data["t"].ravel().tolist() == [1, 2, 3]
    assert back.point_data["v"].tolist() == mixed.point_data["v"].tolist()
    assert [k for k, _ in back.cell_blocks] == ["quad", "tri", "line"]


def test_to_pyvista():
    pts, tris = square()
    c = starplex.Complex(pts, tris, point_data={"h": [0.0, 1.0, 2.0, 3.0]}, cell_data={"t": [5, 6]})
    if importlib.util.find_spec("pyvista") is None:
        with pytest.raises(ImportError, match="pip install pyvista"):
            starplex.to_pyvista(c)
        pytest.skip("SKIPPED: pyvista not installed (checked the ImportError hint)")
    g = starplex.to_pyvista(c)
    assert g.n_points == 4 and g.n_cells == 2
    assert g.point_data["h"].tolist() == [0.0, 1.0, 2.0, 3.0]
    assert g.cell_data["t"].tolist() == [5, 6]
    assert g.cells_dict[5].tolist() == tris.tolist()  # VTK_TRIANGLE


def test_to_pyvista_equals_the_vtu_writer(tmp_path):
    if importlib.util.find_spec("pyvista") is None:
        pytest.skip("SKIPPED: pyvista not installed")
    import pyvista

    pts = np.random.default_rng(0).random((14, 3))
    c = starplex.Complex(
        pts,
        {"hex": [list(range(8))], "prism": [[8, 9, 10, 11, 12, 13]], "tet": [[0, 1, 8, 9]],
         "pyramid": [[2, 3, 10, 11, 12]]},
        cell_data={"t": [1, 2, 3, 4]},
        drop_faces=True,
    )
    g = starplex.to_pyvista(c)
    c.write(tmp_path / "m.vtu")
    r = pyvista.read(tmp_path / "m.vtu")
    assert g.celltypes.tolist() == r.celltypes.tolist()
    assert g.cell_connectivity.tolist() == r.cell_connectivity.tolist()
    assert np.allclose(g.points, r.points)
    assert g.cell_data["t"].tolist() == r.cell_data["t"].ravel().tolist()
