//! Python bindings of starplex: the `starplex._starplex` extension module, re-exported by the
//! pure-Python package `starplex` (see `python/starplex/__init__.py` and its `.pyi` stubs).
//!
//! The binding is thin: arrays in are checked and copied into an [`IndexedComplex`], every query
//! goes through [`starplex::topo::batch`] (the same code as `starplex query --all --out`), and
//! answers leave as NumPy arrays that take ownership of the Rust vectors (no copy). Every call
//! that does real work releases the GIL.
#![allow(clippy::useless_conversion)] // pyo3's generated code

use std::path::PathBuf;
use std::sync::Arc;

use numpy::ndarray::Array2;
use numpy::{
    PyArray1, PyArray2, PyArrayDescrMethods, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyIOError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyInt, PyList, PyString, PyTuple};

use starplex::algo::homology::{homology as run_homology, Field, HomologyOptions};
use starplex::algo::info::{info as run_info, InfoOptions};
use starplex::algo::validate::ValidationReport;
use starplex::buf::Buf;
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, IndexedComplex};
use starplex::io::{self, Format, IoError, IoErrorKind, PolygonMode, ReadOptions};
use starplex::stellar::{StellarOptions, StellarTree as RsStellar};
use starplex::tds::iastar::IaStar as RsIaStar;
use starplex::tds::ig::IncidenceGraph as RsIg;
use starplex::tds::is::Is as RsIs;
use starplex::tds::simplex_tree::{SimplexTree as RsSimplexTree, SimplexTreeOptions};
use starplex::topo::batch::{self, Csr, Relation};
use starplex::topo::naive::VtIndex;
use starplex::topo::{Queries, QueryError};

/// Most simplices a structure may hold (as the command line).
const LIMIT: u128 = 1 << 31;

fn value_err(msg: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(msg.to_string())
}

fn io_err(e: IoError) -> PyErr {
    match e.kind {
        IoErrorKind::Os(_) => PyIOError::new_err(e.to_string()),
        _ => PyValueError::new_err(e.to_string()),
    }
}

fn query_err(e: QueryError) -> PyErr {
    value_err(e)
}

// ---------------------------------------------------------------- arrays in

/// An integer array of ids, checked (non-negative, below `u32::MAX`) and copied to `u32`,
/// with its shape. Anything NumPy can turn into an integer array is accepted; floats, bools,
/// strings and ragged lists are refused with a message naming `what`.
fn index_array(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<(Vec<u32>, Vec<usize>)> {
    let py = obj.py();
    let np = py.import("numpy")?;
    let arr = np
        .call_method1("asarray", (obj,))
        .map_err(|e| value_err(format!("{what}: {}", e.value(py))))?;
    let a = arr
        .cast::<PyUntypedArray>()
        .map_err(|_| PyTypeError::new_err(format!("{what}: not an array")))?;
    let shape = a.shape().to_vec();
    if a.len() == 0 {
        return Ok((Vec::new(), shape));
    }
    let kind = a.dtype().kind();
    let (unsigned, signed) = (kind == b'u', kind == b'i');
    if !unsigned && !signed {
        return Err(PyTypeError::new_err(format!(
            "{what}: expected integer ids, got an array of dtype {}",
            a.dtype().str()?
        )));
    }
    let max = u32::MAX as u64 - 1;
    let bad = |i: usize, v: String| {
        let pos = unravel(i, &shape);
        value_err(format!(
            "{what}{pos}: {v} is not a valid id (ids are 0 ..= {max})"
        ))
    };
    if unsigned {
        let c = np.call_method1("ascontiguousarray", (&arr, "uint64"))?;
        let c = c.cast::<numpy::PyArrayDyn<u64>>()?.readonly();
        let s = c.as_slice()?;
        match py.detach(|| s.iter().position(|&x| x > max)) {
            Some(i) => Err(bad(i, s[i].to_string())),
            None => Ok((py.detach(|| s.iter().map(|&x| x as u32).collect()), shape)),
        }
    } else {
        let c = np.call_method1("ascontiguousarray", (&arr, "int64"))?;
        let c = c.cast::<numpy::PyArrayDyn<i64>>()?.readonly();
        let s = c.as_slice()?;
        match py.detach(|| s.iter().position(|&x| x < 0 || x as u64 > max)) {
            Some(i) => Err(bad(i, s[i].to_string())),
            None => Ok((py.detach(|| s.iter().map(|&x| x as u32).collect()), shape)),
        }
    }
}

/// `[i, j]` for flat index `i` of an array of `shape` (empty for a scalar).
fn unravel(mut i: usize, shape: &[usize]) -> String {
    if shape.is_empty() {
        return String::new();
    }
    let mut idx = vec![0usize; shape.len()];
    for (d, &n) in shape.iter().enumerate().rev() {
        if n > 0 {
            idx[d] = i % n;
            i /= n;
        }
    }
    format!(
        "[{}]",
        idx.iter()
            .map(|x| x.to_string())
            .collect::<Vec<_>>()
            .join(", ")
    )
}

/// Coordinates: an `(n, d)` array of numbers, copied to `f64`.
fn points_array(obj: &Bound<'_, PyAny>) -> PyResult<(Vec<f64>, usize)> {
    let py = obj.py();
    let np = py.import("numpy")?;
    let arr = np
        .call_method1("asarray", (obj,))
        .map_err(|e| value_err(format!("points: {}", e.value(py))))?;
    let a = arr
        .cast::<PyUntypedArray>()
        .map_err(|_| PyTypeError::new_err("points: not an array"))?;
    let kind = a.dtype().kind();
    if !matches!(kind, b'f' | b'i' | b'u') {
        return Err(PyTypeError::new_err(format!(
            "points: expected a real (float or integer) array, got dtype {}",
            a.dtype().str()?
        )));
    }
    if a.ndim() != 2 {
        return Err(value_err(format!(
            "points: expected an (n, d) array, got shape {:?}",
            a.shape()
        )));
    }
    let d = a.shape()[1];
    let c = np.call_method1("ascontiguousarray", (&arr, "float64"))?;
    let c = c.cast::<numpy::PyArray2<f64>>()?.readonly();
    let s = c.as_slice()?;
    Ok((py.detach(|| s.to_vec()), d))
}

/// One block of cells: a kind name (optional) and an `(m, k)` array.
fn cell_block(
    kind: Option<&str>,
    arr: &Bound<'_, PyAny>,
    what: &str,
) -> PyResult<(CellKind, Vec<u32>)> {
    let (v, shape) = index_array(arr, what)?;
    if shape.len() != 2 {
        return Err(value_err(format!(
            "{what}: expected an (m, k) array of vertex ids, got shape {shape:?}"
        )));
    }
    let k = shape[1];
    let kind = match kind {
        Some(name) => CellKind::from_type_name(name).ok_or_else(|| {
            value_err(format!(
                "{what}: unknown cell type '{name}' (expected line, tri, quad, tet, pyramid, prism, hex or simplex_D)"
            ))
        })?,
        None => {
            if k == 0 {
                return Err(value_err(format!("{what}: cells with no vertices")));
            }
            CellKind::simplex(k - 1).ok_or_else(|| {
                value_err(format!(
                    "{what}: a cell of {k} vertices is above the supported simplex dimension"
                ))
            })?
        }
    };
    if kind.n_vertices() != k {
        return Err(value_err(format!(
            "{what}: a {} has {} vertices, not {k}",
            kind.type_name(),
            kind.n_vertices()
        )));
    }
    Ok((kind, v))
}

/// The `cells` argument: one array, a list of arrays or `(kind, array)` pairs, or a dict
/// `{kind: array}`.
fn cell_blocks(obj: &Bound<'_, PyAny>) -> PyResult<Vec<(CellKind, Vec<u32>)>> {
    if let Ok(d) = obj.cast::<PyDict>() {
        let mut out = Vec::new();
        for (k, v) in d.iter() {
            let name: String = k
                .extract()
                .map_err(|_| PyTypeError::new_err("cells: dict keys must be cell type names"))?;
            out.push(cell_block(Some(&name), &v, &format!("cells['{name}']"))?);
        }
        return Ok(out);
    }
    let is_blocks = |items: &Bound<'_, PyAny>| -> PyResult<bool> {
        let n = items.len()?;
        if n == 0 {
            return Ok(false);
        }
        for x in items.try_iter()? {
            let x = x?;
            let ok = x.cast::<PyUntypedArray>().is_ok_and(|a| a.ndim() == 2)
                || x.cast::<PyTuple>().is_ok_and(|t| {
                    t.len() == 2 && t.get_item(0).is_ok_and(|n| n.is_instance_of::<PyString>())
                });
            if !ok {
                return Ok(false);
            }
        }
        Ok(true)
    };
    if (obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>()) && is_blocks(obj)? {
        let mut out = Vec::new();
        for (i, x) in obj.try_iter()?.enumerate() {
            let x = x?;
            let what = format!("cells[{i}]");
            if let Ok(t) = x.cast::<PyTuple>() {
                let name: String = t.get_item(0)?.extract()?;
                out.push(cell_block(Some(&name), &t.get_item(1)?, &what)?);
            } else {
                out.push(cell_block(None, &x, &what)?);
            }
        }
        return Ok(out);
    }
    Ok(vec![cell_block(None, obj, "cells")?])
}

// ---------------------------------------------------------------- arrays out

fn arr1<'py, T: numpy::Element>(py: Python<'py>, v: Vec<T>) -> Bound<'py, PyAny> {
    PyArray1::from_vec(py, v).into_any()
}

fn arr2<'py, T: numpy::Element>(
    py: Python<'py>,
    v: Vec<T>,
    width: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let rows = v.len().checked_div(width).unwrap_or(0);
    let a = Array2::from_shape_vec((rows, width), v).map_err(value_err)?;
    Ok(PyArray2::from_owned_array(py, a).into_any())
}

/// A CSR answer as `(offsets int64, values uint32)`: values are ids (1-D, `width` 0) or
/// simplices of `width` vertices (shape `(n, width)`), offsets count rows.
fn csr_out<'py>(py: Python<'py>, c: Csr, width: usize) -> PyResult<Bound<'py, PyAny>> {
    let offsets: Vec<i64> = c
        .offsets
        .iter()
        .map(|&o| (o / width.max(1) as u64) as i64)
        .collect();
    let values = if width > 0 {
        arr2(py, c.values, width)?
    } else {
        arr1(py, c.values)
    };
    Ok(PyTuple::new(py, [arr1(py, offsets), values])?.into_any())
}

/// Row 0 of a one-item answer (ids: `width` 0; simplices: `(n, width)`).
fn row_out<'py>(py: Python<'py>, c: Csr, width: usize) -> PyResult<Bound<'py, PyAny>> {
    if width > 0 {
        arr2(py, c.values, width)
    } else {
        Ok(arr1(py, c.values))
    }
}

// ---------------------------------------------------------------- Complex

/// A complex: vertices with coordinates and top cells (simplices of any dimension, quads,
/// hexahedra, prisms, pyramids), cell ids in input order.
///
/// `Complex(points, cells)`: `points` an `(n, d)` array of numbers; `cells` an `(m, k)` integer
/// array (k vertices: a (k-1)-simplex), a list of such arrays, a list of `(kind, array)` pairs
/// or a dict `{kind: array}` with kinds `line`, `tri`, `quad`, `tet`, `pyramid`, `prism`, `hex`,
/// `simplex_D`. Duplicate cells and cells that are faces of others are errors unless
/// `drop_duplicates` / `drop_faces`.
///
/// >>> import numpy as np, starplex
/// >>> c = starplex.Complex(np.eye(3), [[0, 1, 2]])
/// >>> c.n_vertices, c.n_cells, c.dim
/// (3, 1, 2)
/// >>> q = starplex.Complex(np.zeros((6, 3)), {"quad": [[0, 1, 2, 3]], "tri": [[2, 3, 4]], "line": [[4, 5]]})
/// >>> [k for k, _ in q.cell_blocks]
/// ['quad', 'tri', 'line']
#[pyclass(frozen, module = "starplex._starplex")]
struct Complex {
    k: Arc<IndexedComplex>,
}

#[pymethods]
impl Complex {
    #[new]
    #[pyo3(signature = (points, cells, *, drop_faces = false, drop_duplicates = false))]
    fn new(
        py: Python<'_>,
        points: &Bound<'_, PyAny>,
        cells: &Bound<'_, PyAny>,
        drop_faces: bool,
        drop_duplicates: bool,
    ) -> PyResult<Self> {
        let (coords, d) = points_array(points)?;
        let blocks = cell_blocks(cells)?;
        let opts = BuildOptions {
            drop_face_cells: drop_faces,
            drop_duplicates,
            trust_maximality: false,
        };
        let k = py
            .detach(|| {
                let blocks = blocks.into_iter().map(|(k, v)| (k, Buf::from(v))).collect();
                IndexedComplex::from_parts_checked(d, Buf::from(coords), blocks, &opts)
            })
            .map_err(value_err)?;
        Ok(Complex { k: Arc::new(k.0) })
    }

    /// Number of vertices.
    #[getter]
    fn n_vertices(&self) -> usize {
        self.k.n_vertices()
    }

    /// Number of top cells.
    #[getter]
    fn n_cells(&self) -> usize {
        self.k.n_cells()
    }

    /// Coordinates per vertex.
    #[getter]
    fn ambient_dim(&self) -> usize {
        self.k.ambient_dim()
    }

    /// Dimension (of the highest cell), None when there are no cells.
    #[getter]
    fn dim(&self) -> Option<usize> {
        self.k.dim()
    }

    /// The coordinates, an `(n, d)` float64 array (a copy).
    #[getter]
    fn points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        arr2(py, self.k.coords().to_vec(), self.k.ambient_dim())
    }

    /// The cells as `[(kind, (m, k) uint32 array), ...]`, one entry per run of one kind in id
    /// order.
    #[getter]
    fn cell_blocks<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let mut out = Vec::new();
        for b in self.k.blocks() {
            let a = arr2(py, b.vertices.to_vec(), b.kind.n_vertices())?;
            out.push(PyTuple::new(
                py,
                [PyString::new(py, &b.kind.type_name()).into_any(), a],
            )?);
        }
        PyList::new(py, out)
    }

    /// The cells: one `(m, k)` uint32 array when the complex has one kind of cell, else a list
    /// of arrays, one per block of `cell_blocks`.
    #[getter]
    fn cells<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let blocks = self.k.blocks();
        if blocks.len() == 1 {
            return arr2(py, blocks[0].vertices.to_vec(), blocks[0].kind.n_vertices());
        }
        let mut out = Vec::new();
        for b in blocks {
            out.push(arr2(py, b.vertices.to_vec(), b.kind.n_vertices())?);
        }
        Ok(PyList::new(py, out)?.into_any())
    }

    /// Writes the complex; the format comes from `format` or the extension.
    #[pyo3(signature = (path, format = None))]
    fn write(&self, py: Python<'_>, path: PathBuf, format: Option<&str>) -> PyResult<()> {
        let f = match format {
            None => None,
            Some(n) => match Format::from_name(n) {
                Some(f) if f.can_write() => Some(f),
                Some(f) => {
                    return Err(value_err(format!(
                        "format {n}: starplex reads {f} but does not write it"
                    )))
                }
                None => return Err(value_err(format!("{n}: unknown output format"))),
            },
        };
        let k = &self.k;
        py.detach(|| io::write(&path, k, f)).map_err(io_err)
    }

    /// Counts with the keys of `starplex info --json`.
    #[pyo3(signature = (*, max_faces = None, betti = false))]
    fn info<'py>(
        &self,
        py: Python<'py>,
        max_faces: Option<u128>,
        betti: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let mut opts = InfoOptions::default();
        if let Some(m) = max_faces {
            opts.max_faces = m;
        }
        let k = &self.k;
        let (s, b) = py.detach(|| {
            let s = run_info(k, &opts);
            let b = betti.then(|| starplex::algo::homology::betti_z2(k));
            (s, b)
        });
        let d = PyDict::new(py);
        d.set_item("n_vertices", s.n_vertices)?;
        d.set_item("n_isolated_vertices", s.n_isolated_vertices)?;
        d.set_item("ambient_dim", s.ambient_dim)?;
        d.set_item("dim", s.dim)?;
        d.set_item("pure", s.pure)?;
        d.set_item(
            "top_cells",
            s.top_cells
                .into_iter()
                .collect::<Vec<_>>()
                .into_py_dict(py)?,
        )?;
        d.set_item("n_top_cells", s.n_top_cells)?;
        d.set_item("bbox", s.bbox.map(|(lo, hi)| vec![lo, hi]))?;
        d.set_item("f_vector", s.f_vector)?;
        d.set_item(
            "f_vector_estimate",
            s.f_vector_estimate.map(|e| e.to_string()),
        )?;
        d.set_item("euler_characteristic", s.euler_characteristic)?;
        d.set_item("n_boundary_faces", s.n_boundary_faces)?;
        d.set_item(
            "n_faces_shared_by_more_than_2_top_cells",
            s.n_faces_shared_by_more_than_2_top_cells,
        )?;
        d.set_item(
            "faces_by_type",
            match s.faces_by_type {
                Some(m) => Some(m.into_iter().collect::<Vec<_>>().into_py_dict(py)?),
                None => None,
            },
        )?;
        d.set_item("n_connected_components", s.n_connected_components)?;
        match b {
            Some(Ok(b)) => d.set_item("betti_z2", b)?,
            Some(Err(e)) => d.set_item("betti_z2_skipped", e.to_string())?,
            None => {}
        }
        Ok(d)
    }

    /// The validation report of `starplex validate --json`, with every id list complete, as
    /// arrays.
    #[pyo3(signature = (*, kv = None))]
    fn validate<'py>(&self, py: Python<'py>, kv: Option<u32>) -> PyResult<Bound<'py, PyDict>> {
        let k = &self.k;
        let opts = StellarOptions {
            kv,
            ..Default::default()
        };
        let r = py
            .detach(|| RsStellar::build(k, &opts).map(|t| t.validate()))
            .map_err(value_err)?;
        report_dict(py, r)
    }

    /// Betti numbers over a field (`"2"`, a prime `"p"`, `"q"`, or `"z"` with torsion), as
    /// `starplex homology --json`.
    #[pyo3(signature = (field = "2", *, per_component = false))]
    fn homology<'py>(
        &self,
        py: Python<'py>,
        field: &str,
        per_component: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let field = Field::parse(field).map_err(value_err)?;
        let opts = HomologyOptions {
            field,
            per_component,
            ..Default::default()
        };
        let k = &self.k;
        let h = py
            .detach(|| run_homology(&VtIndex::new(k), &opts))
            .map_err(value_err)?;
        let d = PyDict::new(py);
        d.set_item("field", h.field.to_string())?;
        d.set_item("betti", &h.betti)?;
        d.set_item("euler_characteristic", h.euler_characteristic())?;
        d.set_item("critical_cells", &h.critical)?;
        if h.field == Field::Z2 {
            d.set_item("betti_z2", &h.betti)?;
        }
        if h.field == Field::Z {
            let t: Vec<Vec<String>> = h
                .torsion
                .iter()
                .map(|t| t.iter().map(|x| x.to_string()).collect())
                .collect();
            d.set_item("torsion", t)?;
        }
        if let Some(comps) = &h.components {
            let l = PyList::empty(py);
            for c in comps {
                let cd = PyDict::new(py);
                cd.set_item("first_vertex", c.first_vertex)?;
                cd.set_item("betti", &c.betti)?;
                if let Some(s) = &c.surface {
                    let sd = PyDict::new(py);
                    sd.set_item("orientable", s.orientable)?;
                    sd.set_item("genus", s.genus)?;
                    sd.set_item("boundary_loops", s.boundary_loops)?;
                    sd.set_item("euler_characteristic", s.euler_characteristic)?;
                    sd.set_item("summary", s.to_string())?;
                    cd.set_item("surface", sd)?;
                } else {
                    cd.set_item("surface", py.None())?;
                }
                l.append(cd)?;
            }
            d.set_item("components", l)?;
        }
        Ok(d)
    }

    /// The top cells of every vertex, straight from the complex (no structure to build): the
    /// CSR pair `(offsets int64, values uint32)`, cell ids ascending. The fastest whole-mesh VT.
    ///
    /// >>> import numpy as np, starplex
    /// >>> off, cells = starplex.Complex(np.eye(4)[:, :2], [[0, 1, 2], [1, 3, 2]]).vt()
    /// >>> off.tolist(), cells.tolist()
    /// ([0, 1, 3, 5, 6], [0, 0, 1, 0, 1, 1])
    fn vt<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let k = &self.k;
        let c = py.detach(|| k.vertex_cells());
        let offsets: Vec<i64> = c.offsets.iter().map(|&o| o as i64).collect();
        Ok(PyTuple::new(py, [arr1(py, offsets), arr1(py, c.targets)])?.into_any())
    }

    fn __repr__(&self) -> String {
        format!(
            "<starplex.Complex: {} vertices in {}D, {} top cells>",
            self.k.n_vertices(),
            self.k.ambient_dim(),
            self.k.n_cells()
        )
    }
}

use pyo3::types::IntoPyDict;

/// Ids as a uint32 array.
fn ids_out<'py, T: Copy>(py: Python<'py>, v: &[T], f: impl Fn(T) -> u32) -> Bound<'py, PyAny> {
    arr1(py, v.iter().map(|&x| f(x)).collect::<Vec<u32>>())
}

/// Faces of possibly mixed sizes: an `(n, k)` array when all have k vertices, else CSR.
fn faces_out<'py>(
    py: Python<'py>,
    f: &[Vec<starplex::ids::VertexId>],
    dim: i64,
) -> PyResult<Bound<'py, PyAny>> {
    let w = f.first().map_or(dim.max(0) as usize, |x| x.len());
    if f.iter().all(|x| x.len() == w) {
        let v: Vec<u32> = f.iter().flat_map(|x| x.iter().map(|v| v.0)).collect();
        return arr2(py, v, w);
    }
    let mut c = Csr {
        offsets: vec![0],
        values: Vec::new(),
    };
    for x in f {
        c.values.extend(x.iter().map(|v| v.0));
        c.offsets.push(c.values.len() as u64);
    }
    csr_out(py, c, 0)
}

fn report_dict(py: Python<'_>, r: ValidationReport) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    let v = |x: starplex::ids::VertexId| x.0;
    let c = |x: starplex::ids::CellId| x.0;
    let edges = |e: &[[starplex::ids::VertexId; 2]]| {
        arr2(
            py,
            e.iter()
                .flat_map(|e| [e[0].0, e[1].0])
                .collect::<Vec<u32>>(),
            2,
        )
    };
    d.set_item("dim", r.dim)?;
    d.set_item("n_connected_components", r.n_connected_components)?;
    d.set_item("n_boundary_faces", r.boundary_faces.len())?;
    d.set_item(
        "n_faces_shared_by_more_than_2_top_cells",
        r.faces_in_more_than_two_cells.len(),
    )?;
    d.set_item("n_non_manifold_vertices", r.non_manifold_vertices.len())?;
    d.set_item("n_non_manifold_edges", r.non_manifold_edges.len())?;
    d.set_item("n_unknown_vertices", r.unknown_vertices.len())?;
    d.set_item("n_unknown_edges", r.unknown_edges.len())?;
    d.set_item("n_isolated_vertices", r.isolated_vertices.len())?;
    d.set_item("n_lower_dimensional_cells", r.lower_dimensional_cells.len())?;
    d.set_item("n_facet_components", r.n_facet_components)?;
    d.set_item("pure", r.pure)?;
    d.set_item("facet_connected", r.facet_connected)?;
    d.set_item("pseudo_manifold", r.pseudo_manifold)?;
    d.set_item("orientable", r.orientable)?;
    d.set_item("n_cells_to_flip", r.cells_to_flip.as_ref().map(|x| x.len()))?;
    d.set_item(
        "orientation_conflict",
        r.orientation_conflict.map(|(a, b)| (a.0, b.0)),
    )?;
    d.set_item(
        "non_manifold_vertices",
        ids_out(py, &r.non_manifold_vertices, v),
    )?;
    d.set_item("non_manifold_edges", edges(&r.non_manifold_edges)?)?;
    d.set_item("unknown_vertices", ids_out(py, &r.unknown_vertices, v))?;
    d.set_item("unknown_edges", edges(&r.unknown_edges)?)?;
    d.set_item("isolated_vertices", ids_out(py, &r.isolated_vertices, v))?;
    d.set_item(
        "lower_dimensional_cells",
        ids_out(py, &r.lower_dimensional_cells, c),
    )?;
    d.set_item(
        "cells_to_flip",
        r.cells_to_flip.as_ref().map(|x| ids_out(py, x, c)),
    )?;
    d.set_item("boundary_faces", faces_out(py, &r.boundary_faces, r.dim)?)?;
    d.set_item(
        "faces_shared_by_more_than_2_top_cells",
        faces_out(py, &r.faces_in_more_than_two_cells, r.dim)?,
    )?;
    Ok(d)
}

/// Reads a complex from a file (format from `format`, the extension or the content). Bad
/// files raise ValueError naming the file, line and problem; missing ones OSError.
///
/// >>> import starplex, tempfile, os
/// >>> p = os.path.join(tempfile.mkdtemp(), "t.off")
/// >>> _ = open(p, "w").write("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
/// >>> starplex.read(p).cells.tolist()
/// [[0, 1, 2]]
#[pyfunction]
#[pyo3(signature = (path, *, format = None, simplices = false, drop_faces = false, drop_duplicates = false))]
fn read(
    py: Python<'_>,
    path: PathBuf,
    format: Option<&str>,
    simplices: bool,
    drop_faces: bool,
    drop_duplicates: bool,
) -> PyResult<Complex> {
    let format = match format {
        None => None,
        Some(n) => {
            Some(Format::from_name(n).ok_or_else(|| value_err(format!("unknown format '{n}'")))?)
        }
    };
    let mut o = ReadOptions {
        format,
        ..Default::default()
    };
    if simplices {
        o.polygons = PolygonMode::Simplices;
    }
    o.build.drop_face_cells = drop_faces;
    o.build.drop_duplicates = drop_duplicates;
    let r = py.detach(|| io::read(&path, &o)).map_err(io_err)?;
    Ok(Complex {
        k: Arc::new(r.complex),
    })
}

// ---------------------------------------------------------------- structures

/// What every data structure answers (the base class of `StellarTree`, `IaStar`,
/// `SimplexTree`, `IncidenceGraph`, `Is`, `Hasse`).
#[pyclass(subclass, frozen, module = "starplex._starplex")]
struct Structure {
    s: Box<dyn Queries + Send + Sync>,
    name: &'static str,
}

/// The items of a query: one, many, or all.
enum Sel {
    One(u32),
    Many(Vec<u32>),
}

impl Structure {
    fn n_items(&self, r: Relation) -> usize {
        r.n_items(self.s.as_ref())
    }

    /// `ids`: None (all `n` items), an int, or a 1-D array of ids.
    fn select(&self, ids: Option<&Bound<'_, PyAny>>, n: usize, what: &str) -> PyResult<Sel> {
        let Some(obj) = ids else {
            return Ok(Sel::Many(batch::all(n)));
        };
        let (v, shape) = if obj.is_instance_of::<PyInt>() {
            let x: i64 = obj
                .extract()
                .map_err(|_| value_err(format!("{what} {obj}: not a valid id")))?;
            if x < 0 || x >= u32::MAX as i64 {
                return Err(value_err(format!("{what} {x}: not a valid id")));
            }
            (vec![x as u32], vec![])
        } else {
            index_array(obj, &format!("{what} ids"))?
        };
        batch::check_items(&v, n, what).map_err(value_err)?;
        match shape.len() {
            0 => Ok(Sel::One(v[0])),
            1 => Ok(Sel::Many(v)),
            _ => Err(value_err(format!(
                "{what} ids: expected an id or a 1-D array of ids, got shape {shape:?}"
            ))),
        }
    }

    /// `simplices`: None (`default`), an int (one vertex), a 1-D array (vertices) or an
    /// `(m, k)` array of simplices. Returns the flat simplices, their width and whether one was
    /// asked (an int).
    fn simplices(
        &self,
        obj: Option<&Bound<'_, PyAny>>,
        default: impl FnOnce() -> (Vec<u32>, usize),
    ) -> PyResult<(Vec<u32>, usize, bool)> {
        let n = self.s.n_vertices();
        let Some(obj) = obj else {
            let (v, w) = default();
            return Ok((v, w, false));
        };
        if obj.is_instance_of::<PyInt>() {
            return match self.select(Some(obj), n, "vertex")? {
                Sel::One(v) => Ok((vec![v], 1, true)),
                Sel::Many(v) => Ok((v, 1, false)),
            };
        }
        let (v, shape) = index_array(obj, "simplices")?;
        batch::check_items(&v, n, "vertex").map_err(value_err)?;
        match shape.len() {
            1 => Ok((v, 1, false)),
            2 => Ok((v, shape[1], false)),
            _ => Err(value_err(format!(
                "simplices: expected an id, a 1-D array of vertex ids or an (m, k) array of simplices, got shape {shape:?}"
            ))),
        }
    }

    fn relation<'py>(
        &self,
        py: Python<'py>,
        r: Relation,
        ids: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let sel = self.select(ids, self.n_items(r), r.item())?;
        let s = self.s.as_ref();
        match sel {
            Sel::One(i) => {
                let c = py.detach(|| batch::gather(s, r, &[i])).map_err(query_err)?;
                row_out(py, c, 0)
            }
            Sel::Many(items) => {
                let c = py
                    .detach(|| batch::gather(s, r, &items))
                    .map_err(query_err)?;
                csr_out(py, c, 0)
            }
        }
    }

    fn levels<'py>(
        &self,
        py: Python<'py>,
        link: bool,
        ids: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let sel = self.select(ids, self.s.n_vertices(), "vertex")?;
        let s = self.s.as_ref();
        let (items, one) = match sel {
            Sel::One(i) => (vec![i], true),
            Sel::Many(v) => (v, false),
        };
        let lv = py
            .detach(|| batch::levels(s, link, &items))
            .map_err(query_err)?;
        let out = PyList::empty(py);
        for (p, c) in lv.into_iter().enumerate() {
            if one {
                out.append(row_out(py, c, p + 1)?)?;
            } else {
                out.append(csr_out(py, c, p + 1)?)?;
            }
        }
        Ok(out.into_any())
    }

    fn answer_simplices<'py>(
        &self,
        py: Python<'py>,
        (v, w, one): (Vec<u32>, usize, bool),
        out_width: Option<usize>,
        f: impl FnOnce(&(dyn Queries + Send + Sync), &[u32], usize) -> Result<Csr, QueryError> + Send,
    ) -> PyResult<Bound<'py, PyAny>> {
        let s = self.s.as_ref();
        let c = py.detach(|| f(s, &v, w)).map_err(query_err)?;
        let width = out_width.unwrap_or(w);
        if one {
            row_out(py, c, width)
        } else {
            csr_out(py, c, width)
        }
    }
}

#[pymethods]
impl Structure {
    /// Top cells incident to each vertex: an int gives a uint32 array, an array of ids or
    /// None (every vertex) a CSR pair `(offsets, values)`.
    ///
    /// >>> import numpy as np, starplex
    /// >>> s = starplex.IaStar(starplex.Complex(np.eye(4)[:, :2], [[0, 1, 2], [1, 3, 2]]))
    /// >>> s.vt(2).tolist()
    /// [0, 1]
    /// >>> off, val = s.vt([0, 3])
    /// >>> off.tolist(), val.tolist()
    /// ([0, 1, 2], [0, 1])
    #[pyo3(signature = (ids = None))]
    fn vt<'py>(
        &self,
        py: Python<'py>,
        ids: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.relation(py, Relation::Vt, ids)
    }

    /// Vertices adjacent to each vertex.
    #[pyo3(signature = (ids = None))]
    fn vv<'py>(
        &self,
        py: Python<'py>,
        ids: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.relation(py, Relation::Vv, ids)
    }

    /// Vertices of each top cell.
    #[pyo3(signature = (ids = None))]
    fn tv<'py>(
        &self,
        py: Python<'py>,
        ids: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.relation(py, Relation::Tv, ids)
    }

    /// Top cells of the same dimension sharing a facet with each top cell.
    #[pyo3(signature = (ids = None))]
    fn tt<'py>(
        &self,
        py: Python<'py>,
        ids: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.relation(py, Relation::Tt, ids)
    }

    /// Link of each vertex, level by level: for an int, a list whose entry p is the
    /// `(n_p, p + 1)` array of the link's p-simplices; for many ids, entry p is a CSR pair
    /// with `(N_p, p + 1)` values.
    ///
    /// >>> import numpy as np, starplex
    /// >>> s = starplex.SimplexTree(starplex.Complex(np.eye(3), [[0, 1, 2]]))
    /// >>> [a.tolist() for a in s.link(0)]
    /// [[[1], [2]], [[1, 2]]]
    #[pyo3(signature = (ids = None))]
    fn link<'py>(
        &self,
        py: Python<'py>,
        ids: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.levels(py, true, ids)
    }

    /// Star of each vertex, level by level.
    #[pyo3(signature = (ids = None))]
    fn star<'py>(
        &self,
        py: Python<'py>,
        ids: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.levels(py, false, ids)
    }

    /// The q-faces of each simplex (default: every top cell): `simplices` an `(m, k)` array
    /// (CSR answer with `(N, q + 1)` values), a 1-D array of vertices, or one int.
    ///
    /// >>> import numpy as np, starplex
    /// >>> s = starplex.IncidenceGraph(starplex.Complex(np.eye(3), [[0, 1, 2]]))
    /// >>> off, faces = s.boundary(q=1)
    /// >>> faces.tolist()
    /// [[0, 1], [0, 2], [1, 2]]
    #[pyo3(signature = (simplices = None, q = 0))]
    fn boundary<'py>(
        &self,
        py: Python<'py>,
        simplices: Option<&Bound<'py, PyAny>>,
        q: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        let tops = || self.uniform_tops();
        let sel = match simplices {
            None => {
                let (v, w) = tops()?;
                (v, w, false)
            }
            some => self.simplices(some, || (Vec::new(), 0))?,
        };
        self.answer_simplices(py, sel, Some(q + 1), move |s, v, w| {
            batch::boundary(s, v, w, q)
        })
    }

    /// The q-cofaces of each simplex (default: every vertex), as `boundary`.
    ///
    /// >>> import numpy as np, starplex
    /// >>> s = starplex.Is(starplex.Complex(np.eye(3), [[0, 1, 2]]))
    /// >>> s.coboundary(0, q=1).tolist()
    /// [[0, 1], [0, 2]]
    /// >>> s.coboundary(np.array([[0, 1]]), q=2)[1].tolist()
    /// [[0, 1, 2]]
    #[pyo3(signature = (simplices = None, q = 1))]
    fn coboundary<'py>(
        &self,
        py: Python<'py>,
        simplices: Option<&Bound<'py, PyAny>>,
        q: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        let n = self.s.n_vertices();
        let sel = self.simplices(simplices, || (batch::all(n), 1))?;
        self.answer_simplices(py, sel, Some(q + 1), move |s, v, w| {
            batch::coboundary(s, v, w, q)
        })
    }

    /// The simplices adjacent to each simplex (default: every vertex), as `boundary`.
    ///
    /// >>> import numpy as np, starplex
    /// >>> s = starplex.Hasse(starplex.Complex(np.eye(4)[:, :2], [[0, 1, 2], [1, 3, 2]]))
    /// >>> s.adjacency(np.array([[0, 1, 2]]))[1].tolist()
    /// [[1, 2, 3]]
    #[pyo3(signature = (simplices = None))]
    fn adjacency<'py>(
        &self,
        py: Python<'py>,
        simplices: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let n = self.s.n_vertices();
        let sel = self.simplices(simplices, || (batch::all(n), 1))?;
        self.answer_simplices(py, sel, None, |s, v, w| batch::adjacent(s, v, w))
    }

    /// Every p-simplex, a `(n_p, p + 1)` uint32 array.
    ///
    /// >>> import numpy as np, starplex
    /// >>> starplex.SimplexTree(starplex.Complex(np.eye(3), [[0, 1, 2]])).faces(1).tolist()
    /// [[0, 1], [0, 2], [1, 2]]
    fn faces<'py>(&self, py: Python<'py>, p: usize) -> PyResult<Bound<'py, PyAny>> {
        let s = self.s.as_ref();
        let v = py.detach(|| batch::faces(s, p)).map_err(query_err)?;
        arr2(py, v, p + 1)
    }

    /// Number of simplices per dimension.
    fn f_vector(&self, py: Python<'_>) -> PyResult<Vec<u64>> {
        let s = self.s.as_ref();
        py.detach(|| s.f_vector()).map_err(query_err)
    }

    /// Number of vertices.
    #[getter]
    fn n_vertices(&self) -> usize {
        self.s.n_vertices()
    }

    /// Number of top cells.
    #[getter]
    fn n_top_cells(&self) -> usize {
        self.s.n_top_cells()
    }

    /// Bytes the structure holds (as `starplex compare`).
    #[getter]
    fn storage_bytes(&self) -> u64 {
        self.s.bytes()
    }

    fn __repr__(&self) -> String {
        format!(
            "<starplex.{}: {} vertices, {} top cells>",
            self.name,
            self.s.n_vertices(),
            self.s.n_top_cells()
        )
    }
}

impl Structure {
    /// Every top cell as a simplex, when all have the same number of vertices.
    fn uniform_tops(&self) -> PyResult<(Vec<u32>, usize)> {
        let n = self.s.n_top_cells();
        let c = batch::gather(self.s.as_ref(), Relation::Tv, &batch::all(n)).map_err(query_err)?;
        let w = if n == 0 { 0 } else { c.row(0).len() };
        if (0..n).any(|i| c.row(i).len() != w) {
            return Err(value_err(
                "boundary of every top cell: the top cells have different sizes; pass the simplices",
            ));
        }
        Ok((c.values, w))
    }
}

fn structure(
    py: Python<'_>,
    name: &'static str,
    build: impl FnOnce() -> Result<Box<dyn Queries + Send + Sync>, String> + Send,
) -> PyResult<PyClassInitializer<Structure>> {
    let s = py.detach(build).map_err(value_err)?;
    Ok(PyClassInitializer::from(Structure { s, name }))
}

macro_rules! structure_class {
    ($name:ident, $doc:literal, |$k:ident| $build:expr) => {
        #[doc = $doc]
        #[pyclass(extends = Structure, frozen, module = "starplex._starplex")]
        struct $name;

        #[pymethods]
        impl $name {
            #[new]
            fn new(py: Python<'_>, c: PyRef<'_, Complex>) -> PyResult<PyClassInitializer<Self>> {
                let $k = Arc::clone(&c.k);
                Ok(structure(py, stringify!($name), move || {
                    let b: Box<dyn Queries + Send + Sync> =
                        Box::new($build.map_err(|e| e.to_string())?);
                    Ok(b)
                })?
                .add_subclass($name))
            }
        }
    };
}

structure_class!(
    IaStar,
    "IA*: top simplices (any cells), adjacencies, one top per vertex cluster.",
    |k| RsIaStar::new(&k)
);
structure_class!(
    SimplexTree,
    "Simplex tree (with label lists); simplicial complexes only.",
    |k| RsSimplexTree::new(
        &k,
        &SimplexTreeOptions {
            label_lists: true,
            max_simplices: LIMIT
        }
    )
);
structure_class!(
    IncidenceGraph,
    "Incidence graph: every simplex (or CP face) with full boundary and co-boundary.",
    |k| RsIg::new(&k, LIMIT)
);
structure_class!(
    Is,
    "IS: every simplex, boundary, one coface per link component; simplicial only.",
    |k| RsIs::new(&k, LIMIT)
);
structure_class!(
    Hasse,
    "CASC Hasse diagram: every simplex with up and down incidences; simplicial only.",
    |k| starplex::hasse::HasseQueries::new(&k, LIMIT)
);

/// Stellar tree: leaf-by-leaf spatial index; `kv` is its bucketing threshold.
#[pyclass(extends = Structure, frozen, module = "starplex._starplex")]
struct StellarTree;

#[pymethods]
impl StellarTree {
    #[new]
    #[pyo3(signature = (c, kv = None))]
    fn new(
        py: Python<'_>,
        c: PyRef<'_, Complex>,
        kv: Option<u32>,
    ) -> PyResult<PyClassInitializer<Self>> {
        let k = Arc::clone(&c.k);
        Ok(structure(py, "StellarTree", move || {
            let opts = StellarOptions {
                kv,
                ..Default::default()
            };
            let t = RsStellar::build(&k, &opts).map_err(|e| e.to_string())?;
            let b: Box<dyn Queries + Send + Sync> = Box::new(t);
            Ok(b)
        })?
        .add_subclass(StellarTree))
    }
}

/// The native module; the package `starplex` re-exports it.
#[pymodule]
fn _starplex(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Complex>()?;
    m.add_class::<Structure>()?;
    m.add_class::<StellarTree>()?;
    m.add_class::<IaStar>()?;
    m.add_class::<SimplexTree>()?;
    m.add_class::<IncidenceGraph>()?;
    m.add_class::<Is>()?;
    m.add_class::<Hasse>()?;
    m.add_function(wrap_pyfunction!(read, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
