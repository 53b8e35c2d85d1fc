"""simplify, rips / flag and render from Python."""
import importlib.util
import itertools
import struct
import zlib

import numpy as np
import pytest

import starplex
from conftest import SMALL, need_data


def grid(n=6):
    pts = np.array([[x, y] for y in range(n) for x in range(n)], dtype=float)
    tris = []
    for y in range(n - 1):
        for x in range(n - 1):
            a = y * n + x
            tris += [[a, a + 1, a + n + 1], [a, a + n + 1, a + n]]
    return starplex.Complex(pts, tris)


# ---------------------------------------------------------------- simplify


def trim(betti):
    betti = list(betti)
    while len(betti) > 1 and betti[-1] == 0:
        betti.pop()
    return betti


def test_simplify_homology_keeps_betti_on_small_datasets():
    need_data()
    picked = [(n, p, o) for n, p, o in SMALL if n in ("tri_elephant", "sierp5_xs")]
    if not picked:
        pytest.skip("SKIPPED: tri_elephant / sierp5_xs not found")
    for name, p, oracle in picked:
        c = starplex.read(p)
        target = max(1, c.n_cells // 10)
        small, r = c.simplify(mode="homology", faces=target)
        assert r["mode"] == "homology"
        assert small.n_cells < c.n_cells, name
        assert r["cells"] == [c.n_cells, small.n_cells] or r["cells"] == (c.n_cells, small.n_cells)
        assert r["before"]["betti_z2"] == oracle["betti_z2"], name
        # the top dimension may drop (no 5-simplex left): Betti numbers up to trailing zeros
        assert trim(r["after"]["betti_z2"]) == trim(oracle["betti_z2"]), name
        assert trim(small.homology()["betti"]) == trim(oracle["betti_z2"]), name
        if name == "tri_elephant":  # a surface: the face target is met
            assert small.n_cells <= target
            assert r["topology_kept"] is True


def test_simplify_qem_targets_and_errors():
    c = grid(8)  # 98 triangles, a disc
    small, r = c.simplify(ratio=0.25)
    assert r["mode"] == "qem" and r["target_faces"] in (24, 25)
    assert small.n_cells <= r["target_faces"]
    assert r["after"]["betti_z2"] == [1, 0, 0] and "max_error" in r
    locked, _ = c.simplify(faces=40, lock_boundary=True, report=False)
    assert locked.n_cells < c.n_cells
    on_boundary = {tuple(p) for p in c.points.tolist() if 0 in p or 7 in p}
    assert len(on_boundary) == 28 and on_boundary <= {tuple(p) for p in locked.points.tolist()}
    _, r = c.simplify(vertices=20, report=False)
    assert r["before"] is None and r["vertices"][1] <= 20
    with pytest.raises(ValueError, match="bad target.*ratio is between 0 and 1"):
        c.simplify(ratio=1.5)
    with pytest.raises(ValueError, match="unknown mode"):
        c.simplify(mode="fast")
    q = starplex.Complex(np.eye(4)[:, :3], {"quad": [[0, 1, 2, 3]]})
    with pytest.raises(ValueError, match="is a quad.*triangulate"):
        q.simplify()
    line = starplex.Complex(np.arange(3.0)[:, None], [[0, 1], [1, 2]])
    with pytest.raises(ValueError, match="quadric.*mode='homology'"):
        line.simplify(mode="qem")


# ---------------------------------------------------------------- rips / flag


def brute_f_vector(pts, eps, max_dim):
    """Every clique of the eps-graph up to max_dim + 1 vertices, by extension."""
    d = np.sqrt(((pts[:, None, :] - pts[None, :, :]) ** 2).sum(-1))
    adj = d <= eps
    n = len(pts)
    f = [n]
    level = [(i,) for i in range(n)]
    for _ in range(max_dim):
        nxt = [s + (j,) for s in level for j in range(s[-1] + 1, n) if all(adj[i, j] for i in s)]
        if not nxt:
            break
        f.append(len(nxt))
        level = nxt
    return f


def test_rips_counts_equal_brute_force_and_gudhi():
    rng = np.random.default_rng(7)
    pts = rng.random((40, 3))
    eps = 0.35
    c = starplex.rips(pts, eps, max_dim=3)
    assert c.points.tolist() == pts.tolist()
    ours = c.info()["f_vector"]
    assert ours == brute_f_vector(pts, eps, 3)
    full = starplex.rips(pts, eps)  # maximal cliques, skeleton counted by the structure
    assert starplex.SimplexTree(full).f_vector()[:4] == ours
    # the flag complex of the same graph is the same complex
    i, j = np.nonzero(np.triu(np.sqrt(((pts[:, None] - pts[None]) ** 2).sum(-1)) <= eps, 1))
    fl = starplex.flag(np.stack([i, j], 1), n_vertices=40, max_dim=3)
    assert fl.info()["f_vector"] == ours
    if importlib.util.find_spec("gudhi") is None:
        pytest.skip("SKIPPED: gudhi not installed (brute force checked)")
    import gudhi

    st = gudhi.RipsComplex(points=pts, max_edge_length=eps).create_simplex_tree(max_dimension=3)
    theirs = [0] * (st.dimension() + 1)
    for s, _ in st.get_simplices():
        theirs[len(s) - 1] += 1
    assert ours == theirs


def test_rips_and_flag_errors():
    pts = np.random.default_rng(1).random((10, 2))
    with pytest.raises(ValueError, match="scale"):
        starplex.rips(pts, -1.0)
    with pytest.raises(ValueError, match="exactly one of eps and eps_nn"):
        starplex.rips(pts)
    with pytest.raises(ValueError, match="exactly one"):
        starplex.rips(pts, 0.1, eps_nn=2.0)
    assert starplex.rips(pts, eps_nn=1.5).n_vertices == 10
    with pytest.raises(ValueError, match="max_memory"):
        starplex.rips(pts, 0.5, max_memory=-1)
    with pytest.raises(ValueError, match="budget|memory"):
        starplex.rips(np.random.default_rng(2).random((60, 2)), 10.0, max_memory=1e-9)
    with pytest.raises(ValueError):
        starplex.rips(np.array([[0.0, np.nan], [1.0, 1.0]]), 1.0)
    with pytest.raises(ValueError, match="shape"):
        starplex.flag([0, 1, 2])
    with pytest.raises(ValueError):
        starplex.flag([[0, 0]])  # self-loop
    with pytest.raises(ValueError):
        starplex.flag([[0, 5]], n_vertices=3)
    with pytest.raises(ValueError, match="not a valid id"):
        starplex.flag([[0, -1]])
    assert starplex.flag(np.zeros((0, 2), dtype=int), n_vertices=3).n_vertices == 3


# ---------------------------------------------------------------- render


def png_size(b):
    assert b[:8] == b"\x89PNG\r\n\x1a\n" and b[12:16] == b"IHDR"
    w, h = struct.unpack(">II", b[16:24])
    return w, h


def png_pixels(b):
    """RGB rows of an 8-bit RGB PNG (every filter type), enough to look at the picture."""
    w, h = png_size(b)
    pos, data = 8, b""
    while pos < len(b):
        (n,) = struct.unpack(">I", b[pos:pos + 4])
        if b[pos + 4:pos + 8] == b"IDAT":
            data += b[pos + 8:pos + 8 + n]
        pos += 12 + n
    raw = zlib.decompress(data)
    stride = w * 3
    prev = bytearray(stride)
    rows = []
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - 3] if x >= 3 else 0
            up = prev[x]
            c = prev[x - 3] if x >= 3 else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + up) & 255
            elif f == 3:
                line[x] = (line[x] + (a + up) // 2) & 255
            elif f == 4:
                p = a + up - c
                pa, pb, pc = abs(p - a), abs(p - up), abs(p - c)
                pr = a if pa <= pb and pa <= pc else (up if pb <= pc else c)
                line[x] = (line[x] + pr) & 255
        rows.append(bytes(line))
        prev = line
    return np.frombuffer(b"".join(rows), dtype=np.uint8).reshape(h, w, 3)


def test_render_png_of_the_requested_size(tmp_path):
    c = grid(5)
    png = c.render(size=(120, 90), legend=False)
    assert png_size(png) == (120, 90)
    px = png_pixels(png)
    assert (px != 255).any() and (px == 255).all(axis=2).any()  # a mesh on a white background
    assert png_size(c.render(size="64x32", color="components", edges=True, view="iso")) == (64, 32)
    out = tmp_path / "m.png"
    assert c.render(out, size=(50, 40), view="30,20") is None
    assert png_size(out.read_bytes()) == (50, 40)
    c.render(tmp_path / "m.svg", size=(50, 40))
    assert (tmp_path / "m.svg").read_text().lstrip().startswith("<")
    c.point_data = {"h": c.points[:, 0]}
    c.cell_data = {"part": np.arange(c.n_cells) % 3}
    assert png_size(c.render(size=(40, 30), color=("field", "h"))) == (40, 30)
    assert png_size(c.render(size=(40, 30), color=("label", "part"))) == (40, 30)


def test_render_errors(tmp_path):
    c = grid(3)
    for kw, msg in [
        ({"size": (0, 10)}, "size"),
        ({"size": "big"}, "WIDTHxHEIGHT"),
        ({"size": (100000, 100000)}, "size"),
        ({"color": "rainbow"}, "unknown colour mode"),
        ({"color": "label"}, "needs the attribute's name"),
        ({"color": ("plain", "x")}, "takes no name"),
        ({"view": "diagonal"}, "unknown view"),
        ({"up": "w"}, "expected x, y or z"),
        ({"clip": "w=1"}, "AXIS=VALUE"),
    ]:
        with pytest.raises(ValueError, match=msg):
            c.render(size=kw.pop("size", (20, 20)), **kw)
    with pytest.raises(ValueError, match="png or a .svg"):
        c.render(tmp_path / "m.jpg", size=(20, 20))
    with pytest.raises(ValueError, match="attribute"):
        c.render(size=(20, 20), color=("field", "missing"))
    with pytest.raises(OSError):
        c.render(tmp_path / "no" / "such" / "dir" / "m.png", size=(20, 20))


def bumpy(n=12):
    """A curved surface (smooth and flat shading differ on it)."""
    c = grid(n)
    xy = c.points
    z = np.sin(xy[:, 0] / 2.0) * np.cos(xy[:, 1] / 3.0)
    return starplex.Complex(np.column_stack([xy, z]), c.cell_blocks[0][1])


def test_render_shading_and_camera():
    c = bumpy()
    kw = {"size": (90, 70), "legend": False}
    flat = c.render(**kw)
    assert c.render(shading="flat", **kw) == flat
    assert c.render(shading=True, **kw) == flat
    smooth = png_pixels(c.render(shading="smooth", **kw))
    none = png_pixels(c.render(shading="none", **kw))
    assert c.render(shading=False, **kw) == c.render(shading="none", **kw)
    f = png_pixels(flat)
    assert (smooth != f).any() and (none != f).any() and (smooth != none).any()
    # unshaded: few distinct colours (the plain colour, the background); shaded: many
    assert len(np.unique(none.reshape(-1, 3), axis=0)) < len(np.unique(f.reshape(-1, 3), axis=0))
    eye = c.render(camera=(15.0, -8.0, 9.0), **kw)
    assert eye != flat
    assert c.render(camera="15,-8,9", **kw) == eye
    assert c.render(camera=np.array([15.0, -8.0, 9.0]), **kw) == eye
    aimed = c.render(camera=(15, -8, 9, 0, 0, 0), **kw)
    assert aimed != eye  # another target: another picture
    for bad, msg in [
        ({"shading": "gouraud"}, "shading"),
        ({"shading": 3}, "shading"),
        ({"camera": (1, 2)}, "camera"),
        ({"camera": "1,2,nan"}, "camera"),
        ({"camera": (1, 2, 3), "view": "top"}, "camera and view"),
        ({"camera": (5.5, 5, 0, 5.5, 5, 0)}, "eye"),
    ]:
        with pytest.raises(ValueError, match=msg):
            c.render(**kw, **bad)


# ---------------------------------------------------------------- same as the command line


def test_same_answers_as_the_command_line(cli, tmp_path):
    import subprocess

    def run(*args):
        return subprocess.run([cli, *map(str, args)], capture_output=True, text=True, check=True)

    c = grid(6)
    src = tmp_path / "g.spx"
    c.write(src)
    # simplify
    out = tmp_path / "s.spx"
    import json

    rep = json.loads(run("simplify", src, out, "--mode", "homology", "--faces", 12, "--json").stdout)
    small, r = c.simplify(mode="homology", faces=12)
    k = starplex.read(out)
    assert k.cell_blocks[0][1].tolist() == small.cell_blocks[0][1].tolist()
    for key in ("mode", "n_contractions", "rounds", "target_faces", "topology_kept"):
        assert rep[key] == r[key], key
    assert rep["after"] == r["after"]
    # rips
    pts = np.random.default_rng(3).random((30, 3))
    np.save(tmp_path / "p.npy", pts)
    run("rips", tmp_path / "p.npy", "--eps", 0.4, "--max-dim", 2, "-o", tmp_path / "r.spx")
    k = starplex.read(tmp_path / "r.spx")
    ours = starplex.rips(pts, 0.4, max_dim=2)
    assert [(n, a.tolist()) for n, a in k.cell_blocks] == [
        (n, a.tolist()) for n, a in ours.cell_blocks
    ]
    # render: the same picture, byte for byte
    run("render", src, "-o", tmp_path / "g.png", "--size", "80x60", "--color", "components")
    png = c.render(size=(80, 60), color="components", title="g.spx")
    assert (tmp_path / "g.png").read_bytes() == png
    b = bumpy()
    b.write(tmp_path / "b.spx")
    run("render", tmp_path / "b.spx", "-o", tmp_path / "b.png", "--size", "80x60",
        "--shading", "smooth", "--camera", "15,-8,9,2,2,0")
    png = b.render(size=(80, 60), shading="smooth", camera=(15, -8, 9, 2, 2, 0), title="b.spx")
    assert (tmp_path / "b.png").read_bytes() == png


def test_threads_share_a_complex_while_its_attributes_change():
    """simplify / render / rips run without the GIL while another thread sets attributes."""
    import threading

    c = grid(10)
    want_png = c.render(size=(60, 40))
    want_cells = c.simplify(ratio=0.3, report=False)[0].n_cells
    pts = np.random.default_rng(5).random((50, 3))
    want_f = starplex.rips(pts, 0.3, max_dim=2).info()["f_vector"]
    out, errors = [], []

    def work(i):
        try:
            for _ in range(3):
                if i % 3 == 0:
                    out.append(c.render(size=(60, 40)) == want_png)
                elif i % 3 == 1:
                    out.append(c.simplify(ratio=0.3, report=False)[0].n_cells == want_cells)
                else:
                    out.append(starplex.rips(pts, 0.3, max_dim=2).info()["f_vector"] == want_f)
                c.point_data = {"t": np.full(c.n_vertices, i)}
        except Exception as e:  # noqa: BLE001
            errors.append(e)

    ts = [threading.Thread(target=work, args=(i,)) for i in range(6)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    assert errors == [] and out == [True] * 18
    assert c.point_data["t"].shape == (c.n_vertices, 1)
