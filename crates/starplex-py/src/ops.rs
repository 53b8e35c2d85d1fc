//! Whole-complex operations: `simplify`, `rips` / `flag`, `render` (option parsing, reports).

use std::path::Path;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString, PyTuple};

use starplex::algo::cliques::CliqueOptions;
use starplex::algo::rips::{self, Built, RipsOptions};
use starplex::algo::simplify::{
    simplify, summary, Mode, SimplifyError, SimplifyOptions, SimplifyReport, Target,
    TopologySummary,
};
use starplex::complex::IndexedComplex;
use starplex::limits::Limits;
use starplex::render::{self, Clip, ColorMode, Eye, RenderOptions, View, COLOR_MODES};

use crate::value_err;

/// The options of `Complex.simplify`, as the command line's flags.
pub(crate) struct SimplifyArgs {
    pub mode: Option<String>,
    pub target: Target,
    pub keep_manifold: bool,
    pub lock_boundary: bool,
    pub report: bool,
}

/// What `simplify` returns before it becomes Python objects.
pub(crate) struct Simplified {
    pub out: IndexedComplex,
    pub report: SimplifyReport,
    pub before: Option<TopologySummary>,
    pub after: Option<TopologySummary>,
}

/// Runs `algo::simplify` (no GIL needed); errors carry the command line's messages and hints.
pub(crate) fn run_simplify(k: &IndexedComplex, a: SimplifyArgs) -> Result<Simplified, String> {
    let mode = match a.mode.as_deref() {
        None => None,
        Some(m) => Some(Mode::parse(m).ok_or_else(|| {
            format!("mode '{m}': unknown mode (use mode='homology' or mode='qem')")
        })?),
    };
    let before = a.report.then(|| summary(k));
    let opts = SimplifyOptions {
        mode,
        target: a.target,
        lock_boundary: a.lock_boundary,
        keep_manifold: a.keep_manifold,
        // as the command line: a gmsh/Medit label attribute is kept by default
        keep_labels: starplex::algo::simplify::default_label_attribute(k.attributes())
            .map(str::to_string),
        keep_vertices: Vec::new(),
        progress: None,
    };
    let (out, report) = simplify(k, &opts).map_err(|e| {
        let hint = match &e {
            SimplifyError::NotSimplicial { .. } => {
                Some("triangulate first: starplex convert --triangulate IN OUT".to_string())
            }
            SimplifyError::BadTarget(_) => Some(format!(
                "the input has {} vertices and {} top cells; ratio is between 0 and 1",
                k.n_vertices(),
                k.n_cells()
            )),
            SimplifyError::NotAMesh => Some("pass mode='homology'".into()),
            _ => None,
        };
        match hint {
            Some(h) => format!("{e} ({h})"),
            None => e.to_string(),
        }
    })?;
    let after = a.report.then(|| summary(&out));
    Ok(Simplified {
        out,
        report,
        before,
        after,
    })
}

fn summary_dict<'py>(py: Python<'py>, s: &TopologySummary) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("n_vertices", s.n_vertices)?;
    d.set_item("n_cells", s.n_cells)?;
    d.set_item("f_vector", &s.f_vector)?;
    d.set_item("euler_characteristic", s.euler_characteristic)?;
    d.set_item("betti_z2", &s.betti)?;
    d.set_item("non_manifold_vertices", s.non_manifold_vertices)?;
    d.set_item("non_manifold_edges", s.non_manifold_edges)?;
    d.set_item("boundary_faces", s.boundary_faces)?;
    Ok(d)
}

/// The report of `starplex simplify --json` (without the file names and report timing).
pub(crate) fn simplify_report<'py>(
    py: Python<'py>,
    k: &IndexedComplex,
    s: &Simplified,
) -> PyResult<Bound<'py, PyDict>> {
    let r = &s.report;
    let d = PyDict::new(py);
    d.set_item("mode", r.mode.name())?;
    d.set_item("target_faces", r.target_faces)?;
    d.set_item("n_contractions", r.n_contractions)?;
    d.set_item("rounds", r.rounds)?;
    d.set_item("time_s", r.time_s)?;
    d.set_item("vertices", (k.n_vertices(), s.out.n_vertices()))?;
    d.set_item("cells", (k.n_cells(), s.out.n_cells()))?;
    if r.mode == Mode::Qem {
        d.set_item("max_error", r.max_error)?;
        d.set_item("mean_error", r.mean_error)?;
    }
    match (&s.before, &s.after) {
        (Some(b), Some(f)) => {
            d.set_item("before", summary_dict(py, b)?)?;
            d.set_item("after", summary_dict(py, f)?)?;
            d.set_item(
                "topology_kept",
                b.betti == f.betti
                    && b.euler_characteristic == f.euler_characteristic
                    && f.non_manifold_vertices <= b.non_manifold_vertices
                    && f.non_manifold_edges <= b.non_manifold_edges,
            )?;
        }
        _ => {
            d.set_item("before", py.None())?;
            d.set_item("after", py.None())?;
        }
    }
    Ok(d)
}

/// The memory budget in GiB (None: the command line's default).
pub(crate) fn budget(max_memory: Option<f64>) -> PyResult<u64> {
    match max_memory {
        None => Ok(rips::default_max_bytes()),
        Some(g) if g.is_finite() && g > 0.0 => Ok((g * (1u64 << 30) as f64) as u64),
        Some(g) => Err(value_err(format!(
            "max_memory {g}: expected a positive number of GiB"
        ))),
    }
}

/// Rips at scale `eps` or `eps_nn` times the median nearest-neighbour distance.
pub(crate) fn run_rips(
    coords: &[f64],
    dim: usize,
    eps: Option<f64>,
    eps_nn: Option<f64>,
    max_dim: Option<usize>,
    max_bytes: u64,
) -> Result<Built, String> {
    let eps = match (eps, eps_nn) {
        (Some(e), None) => e,
        (None, Some(f)) => {
            if !(f.is_finite() && f > 0.0) {
                return Err(format!(
                    "eps_nn {f}: the scale must be a positive finite number"
                ));
            }
            let m = rips::median_nn_distance(coords, dim).map_err(|e| e.to_string())?;
            if m <= 0.0 {
                return Err("the median nearest-neighbour distance is 0 (more than half the points are duplicates): eps_nn gives no scale; give eps".into());
            }
            f * m
        }
        _ => return Err("give exactly one of eps and eps_nn".into()),
    };
    let opts = RipsOptions {
        cliques: CliqueOptions {
            max_dim,
            limits: Limits::with_memory(max_bytes),
            progress: None,
        },
        max_dim,
    };
    rips::rips_complex(coords, dim, eps, &opts)
        .map_err(|e| format!("{e} (use a smaller eps, a max_dim, or a larger max_memory)"))
}

/// The flag complex of an edge list.
pub(crate) fn run_flag(
    n: usize,
    edges: &[(u32, u32)],
    max_dim: Option<usize>,
    max_bytes: u64,
) -> Result<Built, String> {
    let opts = RipsOptions {
        cliques: CliqueOptions {
            max_dim,
            limits: Limits::with_memory(max_bytes),
            progress: None,
        },
        max_dim,
    };
    rips::flag_complex(n, edges, &opts)
        .map_err(|e| format!("{e} (use a max_dim, or a larger max_memory)"))
}

/// `size`: `(width, height)` or `"WxH"`.
fn parse_size(obj: &Bound<'_, PyAny>) -> PyResult<(u32, u32)> {
    let (w, h): (i64, i64) = if let Ok(s) = obj.cast::<PyString>() {
        let s = s.to_str()?;
        let err = || {
            value_err(format!(
                "size '{s}': expected 'WIDTHxHEIGHT' or (width, height)"
            ))
        };
        let (w, h) = s.split_once(['x', 'X']).ok_or_else(err)?;
        (
            w.trim().parse().map_err(|_| err())?,
            h.trim().parse().map_err(|_| err())?,
        )
    } else {
        obj.extract()
            .map_err(|_| value_err(format!("size {obj}: expected (width, height) or 'WxH'")))?
    };
    if w < 0 || h < 0 {
        return Err(value_err(format!("size ({w}, {h}): sizes are positive")));
    }
    render::check_size(w as u64, h as u64)
        .map_err(|e| value_err(format!("size ({w}, {h}): {e}")))?;
    Ok((w as u32, h as u32))
}

/// `color`: a mode name, or `(mode, attribute)` for `label` / `field`.
fn parse_colour(obj: &Bound<'_, PyAny>) -> PyResult<(ColorMode, Option<String>)> {
    let (name, attr): (String, Option<String>) = if let Ok(s) = obj.extract::<String>() {
        (s, None)
    } else if let Ok(t) = obj.cast::<PyTuple>() {
        if t.len() != 2 {
            return Err(value_err(format!(
                "color {obj}: expected a mode or (mode, name)"
            )));
        }
        (t.get_item(0)?.extract()?, Some(t.get_item(1)?.extract()?))
    } else {
        return Err(value_err(format!(
            "color {obj}: expected a mode or (mode, name)"
        )));
    };
    let m = ColorMode::from_name(&name).ok_or_else(|| {
        value_err(format!(
            "color '{name}': unknown colour mode (colour modes: {COLOR_MODES}; ('label', NAME): a cell attribute, ('field', NAME): a vertex attribute)"
        ))
    })?;
    let needs = matches!(m, ColorMode::Label | ColorMode::Field);
    match (needs, attr) {
        (true, None) => Err(value_err(format!(
            "color '{name}' needs the attribute's name: color=('{name}', NAME)"
        ))),
        (false, Some(a)) => Err(value_err(format!(
            "color '{name}' takes no name (got '{a}')"
        ))),
        (_, a) => Ok((m, a)),
    }
}

/// The render options from the keyword arguments.
#[allow(clippy::too_many_arguments)]
pub(crate) fn render_options(
    size: &Bound<'_, PyAny>,
    color: &Bound<'_, PyAny>,
    view: Option<&str>,
    up: &str,
    edges: bool,
    clip: Option<&str>,
    shading: Option<&Bound<'_, PyAny>>,
    legend: bool,
    title: Option<String>,
    kv: Option<u32>,
    camera: Option<&Bound<'_, PyAny>>,
) -> PyResult<RenderOptions> {
    let (width, height) = parse_size(size)?;
    let (colour, attribute) = parse_colour(color)?;
    let view = match view {
        None => None,
        Some(v) => Some(View::from_name(v).ok_or_else(|| {
            value_err(format!(
                "view '{v}': unknown view (views: iso, front, top, side, or 'AZIMUTH,ELEVATION' in degrees)"
            ))
        })?),
    };
    let up = match up {
        "x" | "X" => 0,
        "y" | "Y" => 1,
        "z" | "Z" => 2,
        u => return Err(value_err(format!("up '{u}': expected x, y or z"))),
    };
    let clip = match clip {
        None => None,
        Some(c) => Some(Clip::parse(c).ok_or_else(|| {
            value_err(format!(
                "clip '{c}': expected AXIS=VALUE with AXIS x, y or z (e.g. 'x=0.5')"
            ))
        })?),
    };
    let (shading, smooth) = parse_shading(shading)?;
    let camera = match camera {
        None => None,
        Some(c) => Some(parse_camera(c)?),
    };
    if camera.is_some() && view.is_some() {
        return Err(value_err(
            "camera and view both given: a perspective camera replaces the view; give one",
        ));
    }
    Ok(RenderOptions {
        width,
        height,
        view,
        up,
        colour,
        edges,
        clip,
        shading,
        smooth,
        camera,
        title,
        legend,
        kv,
        attribute,
        ..Default::default()
    })
}

/// `shading`: None or True (flat), False, or "flat" / "smooth" / "none"; as (shading, smooth).
fn parse_shading(s: Option<&Bound<'_, PyAny>>) -> PyResult<(bool, bool)> {
    let Some(s) = s else { return Ok((true, false)) };
    if let Ok(b) = s.extract::<bool>() {
        return Ok((b, false));
    }
    match s.extract::<String>().as_deref() {
        Ok("flat") => Ok((true, false)),
        Ok("smooth") => Ok((true, true)),
        Ok("none") => Ok((false, false)),
        _ => Err(value_err(format!(
            "shading {}: expected 'flat', 'smooth', 'none' or a bool",
            s.repr().map_or_else(|_| "?".to_string(), |r| r.to_string())
        ))),
    }
}

/// `camera`: `(EX, EY, EZ)`, `(EX, EY, EZ, TX, TY, TZ)` or the same comma-separated.
fn parse_camera(c: &Bound<'_, PyAny>) -> PyResult<Eye> {
    let text = match c.extract::<String>() {
        Ok(t) => Some(t),
        Err(_) => c.extract::<Vec<f64>>().ok().map(|v| {
            v.iter()
                .map(|x| x.to_string())
                .collect::<Vec<_>>()
                .join(",")
        }),
    };
    text.as_deref().and_then(Eye::parse).ok_or_else(|| {
        value_err(format!(
            "camera {}: expected (EX, EY, EZ) or (EX, EY, EZ, TX, TY, TZ), finite numbers",
            c.repr().map_or_else(|_| "?".to_string(), |r| r.to_string())
        ))
    })
}

/// PNG or SVG: from the path's extension (bytes: PNG).
pub(crate) fn is_svg(path: Option<&Path>) -> PyResult<bool> {
    let Some(p) = path else { return Ok(false) };
    let ext = p
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("png") => Ok(false),
        Some("svg") => Ok(true),
        _ => Err(PyValueError::new_err(format!(
            "{}: the picture must be a .png or a .svg file",
            p.display()
        ))),
    }
}

/// The picture as encoded bytes (PNG, or SVG text) and the notes of its summary.
pub(crate) fn render_bytes(
    k: &IndexedComplex,
    o: &RenderOptions,
    svg: bool,
) -> Result<(Vec<u8>, Vec<String>), String> {
    let rerr = |e: render::RenderError| format!("render: {e}");
    if svg {
        let (doc, s) = render::render_svg(k, o).map_err(rerr)?;
        return Ok((doc.into_bytes(), s.notes));
    }
    let pic = render::render(k, o).map_err(rerr)?;
    let mut out = Vec::new();
    render::write_png(&pic, &mut out).map_err(|e| format!("render: {e}"))?;
    Ok((out, pic.summary.notes))
}
