//! Attributes in and out: a dict `name -> array` per target (vertices, cells), each array
//! `(n, components)` (1-D for one component), int64 or float64.

use numpy::{PyArrayDescrMethods, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use starplex::attr::{AttrValues, Attribute};

use crate::arr2;

/// The columns of a dict (None: no column). `what` names the argument in messages
/// (`point_data['h']: ...`); lengths are checked by the library against the complex.
pub(crate) fn columns_in(obj: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Vec<Attribute>> {
    let Some(obj) = obj else {
        return Ok(Vec::new());
    };
    if obj.is_none() {
        return Ok(Vec::new());
    }
    let d = obj.cast::<PyDict>().map_err(|_| {
        PyTypeError::new_err(format!(
            "{what}: expected a dict name -> array, got {}",
            obj.get_type()
                .name()
                .map_or_else(|_| "?".into(), |n| n.to_string())
        ))
    })?;
    let mut out = Vec::with_capacity(d.len());
    for (k, v) in d.iter() {
        let name: String = k
            .extract()
            .map_err(|_| PyTypeError::new_err(format!("{what}: keys must be str, got {k}")))?;
        out.push(column(&v, &format!("{what}['{name}']"), name)?);
    }
    Ok(out)
}

fn column(obj: &Bound<'_, PyAny>, what: &str, name: String) -> PyResult<Attribute> {
    let py = obj.py();
    let np = py.import("numpy")?;
    let arr = np
        .call_method1("asarray", (obj,))
        .map_err(|e| PyValueError::new_err(format!("{what}: {}", e.value(py))))?;
    let a = arr
        .cast::<PyUntypedArray>()
        .map_err(|_| PyTypeError::new_err(format!("{what}: not an array")))?;
    let components = match a.shape() {
        [_] => 1,
        [_, c] => *c,
        s => {
            return Err(PyValueError::new_err(format!(
                "{what}: expected an (n,) or (n, components) array, got shape {s:?}"
            )))
        }
    };
    if components == 0 {
        return Err(PyValueError::new_err(format!("{what}: 0 components")));
    }
    let values = match a.dtype().kind() {
        b'b' | b'i' => {
            let c = np.call_method1("ascontiguousarray", (&arr, "int64"))?;
            let c = c.cast::<numpy::PyArrayDyn<i64>>()?.readonly();
            AttrValues::Int(c.as_slice()?.to_vec())
        }
        b'u' => {
            let c = np.call_method1("ascontiguousarray", (&arr, "uint64"))?;
            let c = c.cast::<numpy::PyArrayDyn<u64>>()?.readonly();
            let s = c.as_slice()?;
            if let Some(&x) = s.iter().find(|&&x| x > i64::MAX as u64) {
                return Err(PyValueError::new_err(format!(
                    "{what}: {x} does not fit an int64 attribute"
                )));
            }
            AttrValues::Int(s.iter().map(|&x| x as i64).collect())
        }
        b'f' => {
            let c = np.call_method1("ascontiguousarray", (&arr, "float64"))?;
            let c = c.cast::<numpy::PyArrayDyn<f64>>()?.readonly();
            AttrValues::Float(c.as_slice()?.to_vec())
        }
        _ => {
            return Err(PyTypeError::new_err(format!(
                "{what}: expected an integer or float array, got dtype {}",
                a.dtype().str()?
            )))
        }
    };
    Ok(Attribute {
        name,
        components,
        values,
    })
}

/// The columns as a dict name -> `(n, components)` array (copies).
pub(crate) fn columns_out<'py>(
    py: Python<'py>,
    cols: &[Attribute],
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for c in cols {
        let a = match &c.values {
            AttrValues::Int(v) => arr2(py, v.clone(), c.components)?,
            AttrValues::Float(v) => arr2(py, v.clone(), c.components)?,
        };
        d.set_item(&c.name, a)?;
    }
    Ok(d)
}

/// The `attributes` entry of `info --json`: `{"vertex": [{name, type, components, min, max}],
/// "cell": [...]}`.
pub(crate) fn summary<'py>(
    py: Python<'py>,
    a: &starplex::attr::Attributes,
) -> PyResult<Bound<'py, PyDict>> {
    let cols = |cols: &[Attribute]| -> PyResult<Vec<Bound<'py, PyDict>>> {
        cols.iter()
            .map(|c| {
                let d = PyDict::new(py);
                let r = c.range();
                d.set_item("name", &c.name)?;
                d.set_item("type", c.values.type_name())?;
                d.set_item("components", c.components)?;
                d.set_item("min", r.map(|x| x.0))?;
                d.set_item("max", r.map(|x| x.1))?;
                Ok(d)
            })
            .collect()
    };
    let d = PyDict::new(py);
    d.set_item("vertex", cols(&a.vertex)?)?;
    d.set_item("cell", cols(&a.cell)?)?;
    Ok(d)
}
