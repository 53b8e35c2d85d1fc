//! Python bindings of starplex: the `starplex._starplex` extension module, re-exported by the
//! pure-Python package `starplex` (see `python/starplex/__init__.py` and its `.pyi` stubs).
//!
//! The binding is thin: arrays in are checked and copied into an [`IndexedComplex`], or shared
//! when their memory is immutable (see `frozen`); every query goes through
//! [`starplex::topo::batch`] (the same code as `starplex query --all --out`); answers leave as
//! NumPy arrays that take ownership of the Rust vectors, and a complex's points and cells as
//! read-only views of its memory (no copy either way). Every call that does real work releases
//! the GIL.
#![allow(clippy::useless_conversion)] // pyo3's generated code

mod attrs;
mod hasse_py;
mod ops;

use std::path::PathBuf;
use std::sync::{Arc, RwLock};

use numpy::ndarray::Array2;
use numpy::{
    PyArray1, PyArray2, PyArrayDescrMethods, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyIOError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyInt, PyList, PyString, PyTuple};

use starplex::algo::homology::{homology as run_homology, Field, HomologyOptions};
use starplex::algo::info::{info as run_info, InfoOptions};
use starplex::algo::simplify::Target;
use starplex::algo::validate::ValidationReport;
use starplex::attr::{AttrTarget, Attribute, Attributes};
use starplex::buf::Buf;
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, IndexedComplex};
use starplex::io::{self, Format, IoError, IoErrorKind, PolygonMode, ReadOptions};
use starplex::stellar::{StellarOptions, StellarTree as RsStellar};
use starplex::tds::iastar::IaStar as RsIaStar;
use starplex::tds::ig::IncidenceGraph as RsIg;
use starplex::tds::is::Is as RsIs;
use starplex::tds::simplex_tree::{SimplexTree as RsSimplexTree, SimplexTreeOptions};
use starplex::topo::batch::{self, Answers, Relation};
use starplex::topo::naive::VtIndex;
use starplex::topo::{Queries, QueryError};

/// The budgets of a structure build (as the command line): at most
/// [`starplex::limits::STORED_SIMPLICES`] (2^31) simplices; no memory budget is used there.
const LIMITS: starplex::limits::Limits = starplex::limits::Limits::with_memory(u64::MAX);

fn value_err(msg: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(msg.to_string())
}

fn io_err(e: IoError) -> PyErr {
    use starplex::complex::ComplexError;
    // what to pass to `read` instead, as the command line's hints say it with flags
    let hint = match &e.kind {
        IoErrorKind::CountMismatch(_) => Some("pass lenient=True to read what the file holds"),
        IoErrorKind::Complex(ComplexError::RepeatedVertex { .. }) => {
            Some("pass drop_degenerate=True to drop the cells with a repeated vertex")
        }
        IoErrorKind::Complex(ComplexError::DuplicateCell { .. }) => {
            Some("pass drop_duplicates=True to keep the first copy")
        }
        IoErrorKind::Complex(ComplexError::CellIsFaceOf { .. }) => {
            Some("pass drop_faces=True to keep only the maximal cells")
        }
        _ => None,
    };
    let msg = match hint {
        Some(h) => format!("{e} ({h})"),
        None => e.to_string(),
    };
    match e.kind {
        IoErrorKind::Os(_) => PyIOError::new_err(msg),
        _ => PyValueError::new_err(msg),
    }
}

fn query_err(e: QueryError) -> PyErr {
    value_err(e)
}

// ---------------------------------------------------------------- arrays in

/// An integer array of ids, checked (non-negative, below `u32::MAX`) and copied to `u32`,
/// with its shape. Anything NumPy can turn into an integer array is accepted; floats, bools,
/// strings and ragged lists are refused with a message naming `what`. A C-contiguous `uint32`
/// array whose memory nobody can write ([`frozen`]) is checked and shared, not copied.
fn index_array(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<(Buf<u32>, Vec<usize>)> {
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
        return Ok((Buf::default(), shape));
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
    if let Ok(a32) = arr.cast::<numpy::PyArrayDyn<u32>>() {
        // ids as they are stored: shared when frozen, else one copy
        let shared = frozen(a32)?.and_then(Buf::<u32>::shared);
        let c = np.call_method1("ascontiguousarray", (a32,))?;
        let c = c.cast::<numpy::PyArrayDyn<u32>>()?.readonly();
        let s = c.as_slice()?;
        return match py.detach(|| s.iter().position(|&x| x as u64 > max)) {
            Some(i) => Err(bad(i, s[i].to_string())),
            None => Ok((shared.unwrap_or_else(|| Buf::from(s.to_vec())), shape)),
        };
    }
    if unsigned {
        let c = np.call_method1("ascontiguousarray", (&arr, "uint64"))?;
        let c = c.cast::<numpy::PyArrayDyn<u64>>()?.readonly();
        let s = c.as_slice()?;
        match py.detach(|| s.iter().position(|&x| x > max)) {
            Some(i) => Err(bad(i, s[i].to_string())),
            None => Ok((
                Buf::from(py.detach(|| s.iter().map(|&x| x as u32).collect::<Vec<_>>())),
                shape,
            )),
        }
    } else {
        let c = np.call_method1("ascontiguousarray", (&arr, "int64"))?;
        let c = c.cast::<numpy::PyArrayDyn<i64>>()?.readonly();
        let s = c.as_slice()?;
        match py.detach(|| s.iter().position(|&x| x < 0 || x as u64 > max)) {
            Some(i) => Err(bad(i, s[i].to_string())),
            None => Ok((
                Buf::from(py.detach(|| s.iter().map(|&x| x as u32).collect::<Vec<_>>())),
                shape,
            )),
        }
    }
}

// ---------------------------------------------------------------- arrays shared, not copied

/// The memory of a NumPy array that nobody can write to, kept alive by a reference to the
/// array: what a [`Buf::Shared`] of an input borrows.
struct Frozen {
    _array: Py<PyAny>,
    ptr: *const u8,
    len: usize,
}

// SAFETY: `ptr .. ptr + len` is the data of `_array`, which this value keeps alive; numpy never
// moves an array's data, and `frozen` admitted it only when no one can write it (every array on
// the way to its owner read-only, the owner a read-only buffer). Reading immutable memory from
// any thread is sound, and pyo3 defers the decref of a `Py` dropped without the GIL.
unsafe impl Send for Frozen {}
unsafe impl Sync for Frozen {}

impl starplex::buf::SharedBytes for Frozen {
    fn bytes(&self) -> &[u8] {
        // SAFETY: see the `Send`/`Sync` impls: valid, immutable memory for the value's life
        unsafe { std::slice::from_raw_parts(self.ptr, self.len) }
    }
}

/// `a`'s bytes, for sharing without a copy, when `a` is C-contiguous and aligned and its memory
/// is immutable: `a` and every array it views are read-only, and the memory's owner is not an
/// array (whose flag could be set back to writeable) but an object with a read-only buffer — a
/// read-only memory map (`np.load(f, mmap_mode="r")`), `bytes`, or a complex whose views
/// (`c.points`, `c.cells`) these are. `None` otherwise (the caller copies).
fn frozen<T: numpy::Element>(
    a: &Bound<'_, numpy::PyArrayDyn<T>>,
) -> PyResult<Option<Arc<dyn starplex::buf::SharedBytes>>> {
    if !a.is_c_contiguous() || !a.is_aligned() || !a.dtype().is_native_byteorder().unwrap_or(false)
    {
        return Ok(None);
    }
    let py = a.py();
    let mut x = a.clone().into_any();
    while let Ok(arr) = x.cast::<PyUntypedArray>() {
        let writeable: bool = arr.getattr("flags")?.getattr("writeable")?.extract()?;
        if writeable {
            return Ok(None);
        }
        let base = arr.getattr("base")?;
        if base.is_none() {
            return Ok(None);
        }
        x = base;
    }
    if x.is_instance_of::<ComplexMemory>() {
        return Ok(Some(shared_bytes(a)));
    }
    let readonly = py
        .import("builtins")?
        .getattr("memoryview")?
        .call1((&x,))
        .and_then(|m| {
            let r = m.getattr("readonly")?.extract::<bool>();
            m.call_method0("release")?;
            r
        });
    if !matches!(readonly, Ok(true)) {
        return Ok(None);
    }
    Ok(Some(shared_bytes(a)))
}

/// The bytes of `a` (C-contiguous), kept alive by a reference to it.
fn shared_bytes<T: numpy::Element>(
    a: &Bound<'_, numpy::PyArrayDyn<T>>,
) -> Arc<dyn starplex::buf::SharedBytes> {
    Arc::new(Frozen {
        _array: a.clone().into_any().unbind(),
        ptr: a.data() as *const u8,
        len: a.len() * std::mem::size_of::<T>(),
    })
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

/// Coordinates: an `(n, d)` array of numbers, copied to `f64`, or shared without a copy when it
/// is a read-only C-contiguous `float64` array whose memory nobody can write ([`frozen`]).
fn points_array(obj: &Bound<'_, PyAny>) -> PyResult<(Buf<f64>, usize)> {
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
    if let Ok(a64) = arr.cast::<numpy::PyArrayDyn<f64>>()
        && let Some(b) = frozen(a64)?.and_then(Buf::<f64>::shared)
    {
        return Ok((b, d));
    }
    let c = np.call_method1("ascontiguousarray", (&arr, "float64"))?;
    let c = c.cast::<numpy::PyArray2<f64>>()?.readonly();
    let s = c.as_slice()?;
    Ok((Buf::from(py.detach(|| s.to_vec())), d))
}

/// One block of cells: a kind name (optional) and an `(m, k)` array.
fn cell_block(
    kind: Option<&str>,
    arr: &Bound<'_, PyAny>,
    what: &str,
) -> PyResult<(CellKind, Buf<u32>)> {
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
fn cell_blocks(obj: &Bound<'_, PyAny>) -> PyResult<Vec<(CellKind, Buf<u32>)>> {
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

/// Keeps a complex alive for the NumPy arrays that view its memory (their `base`).
#[pyclass(frozen, module = "starplex._starplex")]
struct ComplexMemory(#[allow(dead_code)] Arc<IndexedComplex>);

/// `data` (inside `k`) as a read-only `(rows, width)` array without a copy; its base keeps `k`
/// alive. NumPy cannot make it writeable again: its base exports no buffer.
fn view2<'py, T: numpy::Element>(
    py: Python<'py>,
    k: &Arc<IndexedComplex>,
    data: &[T],
    width: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let rows = data.len().checked_div(width).unwrap_or(0);
    let v = numpy::ndarray::ArrayView2::from_shape((rows, width), data).map_err(value_err)?;
    let keep = Bound::new(py, ComplexMemory(Arc::clone(k)))?.into_any();
    // SAFETY: `data` lies in `k`, which `keep` (the array's base) keeps alive; a complex behind
    // an `Arc` is never changed in place while another `Arc` holds it (`Complex`'s setters go
    // through `Arc::make_mut`, which copies then), so the memory neither moves nor changes.
    let a = unsafe { PyArray2::borrow_from_array(&v, keep) };
    a.readwrite().make_nonwriteable();
    Ok(a.into_any())
}

/// A CSR answer as `(offsets int64, values uint32)`: values are ids (1-D, `width` 0) or
/// simplices of `width` vertices (shape `(n, width)`), offsets count rows.
fn csr_out<'py>(py: Python<'py>, c: Answers, width: usize) -> PyResult<Bound<'py, PyAny>> {
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
fn row_out<'py>(py: Python<'py>, c: Answers, width: usize) -> PyResult<Bound<'py, PyAny>> {
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
/// Arrays are copied, except a C-contiguous `float64` points array or `uint32` cell array whose
/// memory nobody can write (a read-only memory map such as `np.load(f, mmap_mode="r")`, an
/// array over `bytes`, another complex's `points` / `cells`): those are shared, not copied.
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
    /// Swapped whole by the attribute setters; every method works on its own `Arc`.
    k: RwLock<Arc<IndexedComplex>>,
}

impl Complex {
    fn wrap(k: IndexedComplex) -> Complex {
        Complex {
            k: RwLock::new(Arc::new(k)),
        }
    }

    /// Replaces the columns of `target` (checked by the library; unchanged on error).
    fn set_columns(&self, target: AttrTarget, cols: Vec<Attribute>) -> PyResult<()> {
        let mut g = self.k.write().unwrap_or_else(|e| e.into_inner());
        let mut a = g.attributes().clone();
        match target {
            AttrTarget::Vertex => a.vertex = cols,
            AttrTarget::Cell => a.cell = cols,
        }
        // checked first, so that a refused column costs no copy of a shared complex
        a.check(g.n_vertices(), g.n_cells()).map_err(value_err)?;
        Arc::make_mut(&mut g).set_attributes(a).map_err(value_err)
    }

    /// The complex now (cheap: an `Arc`).
    fn k(&self) -> Arc<IndexedComplex> {
        Arc::clone(&self.k.read().unwrap_or_else(|e| e.into_inner()))
    }
}

#[pymethods]
impl Complex {
    #[new]
    #[pyo3(signature = (points, cells, *, drop_faces = false, drop_duplicates = false, point_data = None, cell_data = None))]
    fn new(
        py: Python<'_>,
        points: &Bound<'_, PyAny>,
        cells: &Bound<'_, PyAny>,
        drop_faces: bool,
        drop_duplicates: bool,
        point_data: Option<&Bound<'_, PyAny>>,
        cell_data: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let (coords, d) = points_array(points)?;
        let blocks = cell_blocks(cells)?;
        let attrs = Attributes {
            vertex: attrs::columns_in(point_data, "point_data")?,
            cell: attrs::columns_in(cell_data, "cell_data")?,
        };
        let opts = BuildOptions {
            drop_face_cells: drop_faces,
            drop_duplicates,
            trust_maximality: false,
            drop_degenerate: false,
        };
        let k = py
            .detach(|| IndexedComplex::from_parts_with_attributes(d, coords, blocks, attrs, &opts))
            .map_err(value_err)?;
        Ok(Complex::wrap(k.0))
    }

    /// The vertex attributes: a dict name -> `(n_vertices, components)` array, int64 or
    /// float64 (a new dict of copies; assign a whole dict to change them).
    ///
    /// >>> import numpy as np, starplex
    /// >>> c = starplex.Complex(np.eye(3), [[0, 1, 2]], point_data={"h": [0.5, 1.5, 2.5]})
    /// >>> c.point_data["h"].tolist()
    /// [[0.5], [1.5], [2.5]]
    /// >>> c.point_data = {"id": np.arange(3)}
    /// >>> c.point_data["id"].dtype.name
    /// 'int64'
    #[getter]
    fn point_data<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        attrs::columns_out(py, &self.k().attributes().vertex)
    }

    #[setter]
    fn set_point_data(&self, value: Option<&Bound<'_, PyAny>>) -> PyResult<()> {
        let cols = attrs::columns_in(value, "point_data")?;
        self.set_columns(AttrTarget::Vertex, cols)
    }

    /// The cell attributes (one item per top cell, in cell id order), as `point_data`.
    ///
    /// >>> import numpy as np, starplex
    /// >>> c = starplex.Complex(np.eye(4)[:, :2], [[0, 1, 2], [1, 3, 2]])
    /// >>> c.cell_data = {"tag": [7, 9]}
    /// >>> c.cell_data["tag"].ravel().tolist()
    /// [7, 9]
    #[getter]
    fn cell_data<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        attrs::columns_out(py, &self.k().attributes().cell)
    }

    #[setter]
    fn set_cell_data(&self, value: Option<&Bound<'_, PyAny>>) -> PyResult<()> {
        let cols = attrs::columns_in(value, "cell_data")?;
        self.set_columns(AttrTarget::Cell, cols)
    }

    /// Number of vertices.
    #[getter]
    fn n_vertices(&self) -> usize {
        self.k().n_vertices()
    }

    /// Number of top cells.
    #[getter]
    fn n_cells(&self) -> usize {
        self.k().n_cells()
    }

    /// Coordinates per vertex.
    #[getter]
    fn ambient_dim(&self) -> usize {
        self.k().ambient_dim()
    }

    /// Dimension (of the highest cell), None when there are no cells.
    #[getter]
    fn dim(&self) -> Option<usize> {
        self.k().dim()
    }

    /// The coordinates, an `(n, d)` float64 array: a read-only view of the complex's memory,
    /// no copy (`np.array(c.points)` for a writeable copy). A complex built from a read-only
    /// memory map (`np.load(f, mmap_mode="r")`) views that map.
    ///
    /// >>> import numpy as np, starplex
    /// >>> c = starplex.Complex(np.eye(3), [[0, 1, 2]])
    /// >>> p = c.points
    /// >>> p.flags.writeable, p.shape
    /// (False, (3, 3))
    #[getter]
    fn points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let k = self.k();
        view2(py, &k, k.coords(), k.ambient_dim())
    }

    /// The cells as `[(kind, (m, k) uint32 array), ...]`, one entry per run of one kind in id
    /// order; read-only views of the complex's memory, as `points`.
    #[getter]
    fn cell_blocks<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let mut out = Vec::new();
        let k = self.k();
        for b in k.blocks() {
            let a = view2(py, &k, &b.vertices, b.kind.n_vertices())?;
            out.push(PyTuple::new(
                py,
                [PyString::new(py, &b.kind.type_name()).into_any(), a],
            )?);
        }
        PyList::new(py, out)
    }

    /// The cells: one `(m, k)` uint32 array when the complex has one kind of cell, else a list
    /// of arrays, one per block of `cell_blocks`; read-only views, as `points`.
    #[getter]
    fn cells<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let k = self.k();
        let blocks = k.blocks();
        if blocks.len() == 1 {
            return view2(py, &k, &blocks[0].vertices, blocks[0].kind.n_vertices());
        }
        let mut out = Vec::new();
        for b in blocks {
            out.push(view2(py, &k, &b.vertices, b.kind.n_vertices())?);
        }
        Ok(PyList::new(py, out)?.into_any())
    }

    /// Writes the complex; the format comes from `format` or the extension. Attributes are
    /// written where the format can hold them (VTK `.vtk`/`.vtu`/`.vtp` all, Medit its
    /// `medit:ref`); a `UserWarning` names the ones a format drops.
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
        let k = &self.k();
        py.detach(|| io::write(&path, k, f)).map_err(io_err)?;
        if let Some(fmt) = f.or_else(|| Format::from_path(&path)) {
            let dropped = fmt.dropped_attributes(k.attributes());
            if !dropped.is_empty() {
                let msg = format!(
                    "the attributes {} are not written: {fmt} cannot hold them (write .vtu, .vtk, .spx or .spb to keep them)",
                    dropped.join(", ")
                );
                let cat = py.get_type::<pyo3::exceptions::PyUserWarning>();
                py.import("warnings")?.call_method1("warn", (msg, cat, 2))?;
            }
        }
        Ok(())
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
            opts.limits.info_faces = m;
        }
        let k = &self.k();
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
        if !k.attributes().is_empty() {
            d.set_item("attributes", attrs::summary(py, k.attributes())?)?;
        }
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
        let k = &self.k();
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
        let k = &self.k();
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
        let k = &self.k();
        let c = py.detach(|| k.vertex_cells());
        let offsets: Vec<i64> = c.offsets.iter().map(|&o| o as i64).collect();
        Ok(PyTuple::new(py, [arr1(py, offsets), arr1(py, c.targets)])?.into_any())
    }

    /// Simplifies by edge contraction that keeps the topology (`starplex simplify`): returns
    /// `(Complex, report)`, the report a dict with the keys of `simplify --json` (`mode`,
    /// `n_contractions`, `vertices`, `cells`, `before`/`after` topology, `topology_kept`, ...).
    ///
    /// `mode`: `"qem"` (quadric error; triangle and tetrahedral meshes, their default) or
    /// `"homology"` (link condition, any simplicial complex). Stop at the first target
    /// reached: `ratio` (fraction of the top cells kept), `faces`, `vertices`, `max_error`
    /// (qem); none: as far as possible. `keep_manifold` (homology: a manifold stays one),
    /// `lock_boundary` (qem: boundary vertices stay), `report=False` skips the before/after
    /// topology (faster). Attributes are not carried.
    ///
    /// >>> import numpy as np, starplex
    /// >>> pts = np.array([[x, y] for y in range(4) for x in range(4)], dtype=float)
    /// >>> tris = [[a, a + 1, a + 5] for a in (0, 1, 2, 4, 5, 6, 8, 9, 10)]
    /// >>> tris += [[a, a + 5, a + 4] for a in (0, 1, 2, 4, 5, 6, 8, 9, 10)]
    /// >>> c = starplex.Complex(pts, tris)
    /// >>> small, r = c.simplify(mode="homology", faces=4, keep_manifold=True)
    /// >>> small.n_cells <= 4, r["topology_kept"], r["after"]["betti_z2"]
    /// (True, True, [1, 0, 0])
    #[pyo3(signature = (*, mode = None, ratio = None, faces = None, vertices = None, max_error = None, keep_manifold = false, lock_boundary = false, report = true))]
    #[allow(clippy::too_many_arguments)]
    fn simplify<'py>(
        &self,
        py: Python<'py>,
        mode: Option<String>,
        ratio: Option<f64>,
        faces: Option<usize>,
        vertices: Option<usize>,
        max_error: Option<f64>,
        keep_manifold: bool,
        lock_boundary: bool,
        report: bool,
    ) -> PyResult<(Complex, Bound<'py, PyDict>)> {
        let k = self.k();
        let args = ops::SimplifyArgs {
            mode,
            target: Target {
                faces,
                vertices,
                ratio,
                max_error,
            },
            keep_manifold,
            lock_boundary,
            report,
        };
        let s = py
            .detach(|| ops::run_simplify(&k, args))
            .map_err(value_err)?;
        let d = ops::simplify_report(py, &k, &s)?;
        Ok((Complex::wrap(s.out), d))
    }

    /// A picture of the complex (`starplex render`): PNG bytes when `path` is None, else
    /// writes `path` (`.png`, or `.svg` with one path per visible face) and returns None.
    ///
    /// `size` `(width, height)` or `"WxH"`; `color` one of plain, blocks, components, defects,
    /// boundary, or `("label", NAME)` (a cell attribute) / `("field", NAME)` (a vertex
    /// attribute); `view` iso, front, top, side or `"AZIMUTH,ELEVATION"` (default: top for a
    /// flat complex, iso otherwise); `up` x, y or z; `clip` `"x=0.5"`; `kv` the Stellar tree
    /// threshold of `color="blocks"`; `shading` "flat" (or True), "smooth" (Gouraud, from
    /// per-vertex normals) or "none" (or False); `camera` a perspective eye `(EX, EY, EZ)`, or
    /// `(EX, EY, EZ, TX, TY, TZ)` with the point looked at, or the same as a comma-separated
    /// string (not with `view`). Notes of the renderer come as `UserWarning`s.
    ///
    /// >>> import numpy as np, starplex
    /// >>> png = starplex.Complex(np.eye(3), [[0, 1, 2]]).render(size=(64, 48))
    /// >>> png[:4], int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")
    /// (b'\x89PNG', 64, 48)
    ///
    /// >>> k = starplex.Complex(np.eye(3), [[0, 1, 2]])
    /// >>> k.render(size=(32, 32), shading="smooth", camera=(2, 2, 2))[:4]
    /// b'\x89PNG'
    #[pyo3(signature = (path = None, *, size = None, color = None, view = None, up = "z", edges = false, clip = None, shading = None, legend = true, title = None, kv = None, camera = None))]
    #[allow(clippy::too_many_arguments)]
    fn render<'py>(
        &self,
        py: Python<'py>,
        path: Option<PathBuf>,
        size: Option<&Bound<'py, PyAny>>,
        color: Option<&Bound<'py, PyAny>>,
        view: Option<&str>,
        up: &str,
        edges: bool,
        clip: Option<&str>,
        shading: Option<&Bound<'py, PyAny>>,
        legend: bool,
        title: Option<String>,
        kv: Option<u32>,
        camera: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Option<Bound<'py, PyBytes>>> {
        let default_size = PyTuple::new(py, [1024u32, 768])?.into_any();
        let plain = PyString::new(py, "plain").into_any();
        let o = ops::render_options(
            size.unwrap_or(&default_size),
            color.unwrap_or(&plain),
            view,
            up,
            edges,
            clip,
            shading,
            legend,
            title,
            kv,
            camera,
        )?;
        let svg = ops::is_svg(path.as_deref())?;
        let k = self.k();
        let (bytes, notes) = py
            .detach(|| ops::render_bytes(&k, &o, svg))
            .map_err(value_err)?;
        for n in notes {
            let cat = py.get_type::<pyo3::exceptions::PyUserWarning>();
            py.import("warnings")?.call_method1("warn", (n, cat, 2))?;
        }
        match path {
            None => Ok(Some(PyBytes::new(py, &bytes))),
            Some(p) => {
                py.detach(|| {
                    io::output::write_with(&p, |w| {
                        w.write_all(&bytes)?;
                        Ok(())
                    })
                })
                .map_err(io_err)?;
                Ok(None)
            }
        }
    }

    fn __repr__(&self) -> String {
        format!(
            "<starplex.Complex: {} vertices in {}D, {} top cells>",
            self.k().n_vertices(),
            self.k().ambient_dim(),
            self.k().n_cells()
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
    let mut c = Answers {
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
/// files raise ValueError naming the file, line and problem, and the option that would read
/// them; missing ones OSError. What the reader changed (polygons split, cells dropped, a
/// header count overruled) is issued as a `UserWarning` per note, as the command line prints
/// `note:` lines.
///
/// Options, as the command line's flags: `simplices` (OFF/PLY/OBJ faces become simplices of
/// their size, not polygons), `drop_faces` (cells that are faces of other cells),
/// `drop_duplicates`, `drop_degenerate` (cells with a repeated vertex), `lenient` (an OFF
/// header whose face count disagrees with the face lines: read the lines that are there).
///
/// >>> import starplex, tempfile, os, warnings
/// >>> p = os.path.join(tempfile.mkdtemp(), "t.off")
/// >>> _ = open(p, "w").write("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
/// >>> starplex.read(p).cells.tolist()
/// [[0, 1, 2]]
/// >>> _ = open(p, "w").write("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 1\n")
/// >>> with warnings.catch_warnings(record=True) as w:
/// ...     warnings.simplefilter("always")
/// ...     c = starplex.read(p, lenient=True, drop_degenerate=True)
/// >>> c.n_cells, len(w)
/// (1, 2)
#[pyfunction]
#[pyo3(signature = (path, *, format = None, simplices = false, drop_faces = false, drop_duplicates = false, drop_degenerate = false, lenient = false))]
#[allow(clippy::too_many_arguments)]
fn read(
    py: Python<'_>,
    path: PathBuf,
    format: Option<&str>,
    simplices: bool,
    drop_faces: bool,
    drop_duplicates: bool,
    drop_degenerate: bool,
    lenient: bool,
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
    o.build.drop_degenerate = drop_degenerate;
    o.lenient = lenient;
    let r = py.detach(|| io::read(&path, &o)).map_err(io_err)?;
    if !r.notes.is_empty() {
        let warn = py.import("warnings")?.getattr("warn")?;
        let category = py.get_type::<pyo3::exceptions::PyUserWarning>();
        for n in &r.notes {
            warn.call1((format!("{}: {n}", path.display()), &category))?;
        }
    }
    Ok(Complex::wrap(r.complex))
}

/// The Vietoris-Rips complex of a point cloud (`starplex rips`), stored by its maximal
/// simplices: `points` an `(n, d)` array; scale `eps` (points at distance <= eps are joined)
/// or `eps_nn` (a multiple of the median nearest-neighbour distance); `max_dim` keeps the
/// K-skeleton; `max_memory` the budget in GiB (default: a third of the available memory).
/// The vertices are the points, in order.
///
/// >>> import numpy as np, starplex
/// >>> square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=float)
/// >>> starplex.rips(square, 1.0).n_cells, starplex.rips(square, 1.5).dim
/// (4, 3)
#[pyfunction]
#[pyo3(signature = (points, eps = None, *, eps_nn = None, max_dim = None, max_memory = None))]
fn rips(
    py: Python<'_>,
    points: &Bound<'_, PyAny>,
    eps: Option<f64>,
    eps_nn: Option<f64>,
    max_dim: Option<usize>,
    max_memory: Option<f64>,
) -> PyResult<Complex> {
    let (coords, d) = points_array(points)?;
    let max_bytes = ops::budget(max_memory)?;
    let b = py
        .detach(|| ops::run_rips(&coords, d, eps, eps_nn, max_dim, max_bytes))
        .map_err(value_err)?;
    Ok(Complex::wrap(b.complex))
}

/// The flag (clique) complex of a graph (`starplex flag`): `edges` an `(m, 2)` array of
/// vertex ids, `n_vertices` (default: the largest id + 1); vertices get one coordinate, their
/// id. `max_dim` and `max_memory` as `rips`.
///
/// >>> import starplex
/// >>> c = starplex.flag([[0, 1], [1, 2], [2, 0], [2, 3]], n_vertices=5)
/// >>> [(kind, a.tolist()) for kind, a in c.cell_blocks]
/// [('line', [[2, 3]]), ('tri', [[0, 1, 2]])]
#[pyfunction]
#[pyo3(signature = (edges, n_vertices = None, *, max_dim = None, max_memory = None))]
fn flag(
    py: Python<'_>,
    edges: &Bound<'_, PyAny>,
    n_vertices: Option<usize>,
    max_dim: Option<usize>,
    max_memory: Option<f64>,
) -> PyResult<Complex> {
    let (v, shape) = index_array(edges, "edges")?;
    if !(shape.len() == 2 && shape[1] == 2 || v.is_empty() && shape.len() <= 2) {
        return Err(value_err(format!(
            "edges: expected an (m, 2) array of vertex ids, got shape {shape:?}"
        )));
    }
    let pairs: Vec<(u32, u32)> = v.chunks_exact(2).map(|e| (e[0], e[1])).collect();
    let n = n_vertices.unwrap_or_else(|| v.iter().max().map_or(0, |&m| m as usize + 1));
    let max_bytes = ops::budget(max_memory)?;
    let b = py
        .detach(|| ops::run_flag(n, &pairs, max_dim, max_bytes))
        .map_err(value_err)?;
    Ok(Complex::wrap(b.complex))
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
            let (v, shape) = index_array(obj, &format!("{what} ids"))?;
            (v.into_vec(), shape)
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
        let v = v.into_vec();
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
        f: impl FnOnce(&(dyn Queries + Send + Sync), &[u32], usize) -> Result<Answers, QueryError>
            + Send,
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
                let $k = c.k();
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
            limits: LIMITS
        }
    )
);
structure_class!(
    IncidenceGraph,
    "Incidence graph: every simplex (or CP face) with full boundary and co-boundary.",
    |k| RsIg::new(&k, &LIMITS)
);
structure_class!(
    Is,
    "IS: every simplex, boundary, one coface per link component; simplicial only.",
    |k| RsIs::new(&k, &LIMITS)
);
structure_class!(
    Hasse,
    "CASC Hasse diagram: every simplex with up and down incidences; simplicial only.",
    |k| starplex::hasse::HasseQueries::new(&k, &LIMITS)
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
        let k = c.k();
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
    m.add_class::<hasse_py::HasseComplex>()?;
    m.add_function(wrap_pyfunction!(read, m)?)?;
    m.add_function(wrap_pyfunction!(rips, m)?)?;
    m.add_function(wrap_pyfunction!(flag, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
