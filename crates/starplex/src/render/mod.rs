//! Pictures of a complex, headless: a software rasterizer with a depth buffer and flat or smooth
//! (Gouraud) shading (`starplex render`), seen along a named direction (orthographic) or from an
//! eye point ([`Eye`], perspective). What is drawn: triangles and quads; the boundary surface of
//! the 3-cells (tets, hexes, prisms, pyramids, mixed), optionally cut open by a clipping plane;
//! 1-cells as lines, 0-cells and isolated vertices as dots; higher simplices by their
//! 2-skeleton, all projected from the first three coordinates. Colours: plain, Stellar leaf
//! blocks, connected components, defects from [`validate`](crate::algo::validate) drawn on top
//! as markers (with inverted cells), the boundary, a cell label attribute (a legend entry per
//! value) and a vertex field attribute (interpolated, with a colour bar). Output: an RGB pixel buffer ([`render`], PNG through `write_png` with the `render`
//! feature) or an SVG document with one path per visible face ([`render_svg`]).
//!
//! ```
//! use starplex::cell::CellKind;
//! use starplex::complex::IndexedComplex;
//! use starplex::render::{render, RenderOptions, View};
//! let k = IndexedComplex::from_parts(2, vec![0., 0., 1., 0., 0., 1.].into(),
//!     vec![(CellKind::Simplex(2), vec![0, 1, 2].into())]).unwrap();
//! let opts = RenderOptions { width: 100, height: 100, view: Some(View::Top), legend: false, ..Default::default() };
//! let pic = render(&k, &opts).unwrap();
//! let (x, y) = pic.project(&[0.2, 0.2]); // inside the triangle
//! assert_ne!(pic.pixel(x as usize, y as usize), 0xFFFFFF); // not the background
//! ```
mod camera;
mod colour;
mod font;
mod paint;
mod raster;
mod scene;
mod svg;

use crate::complex::IndexedComplex;
use crate::stellar::{StellarError, StellarTree};

use camera::Camera;
use raster::{Canvas, NO_FACE};
use scene::{Scene, NO_CELL};

/// How faces are coloured.
///
/// ```
/// use starplex::render::ColorMode;
/// assert_eq!(ColorMode::from_name("blocks"), Some(ColorMode::Blocks));
/// assert_eq!(ColorMode::Blocks.name(), "blocks");
/// assert_eq!(ColorMode::from_name("rainbow"), None);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ColorMode {
    /// One colour, shaded.
    #[default]
    Plain,
    /// One colour per Stellar tree leaf (the leaf of the cell's first vertex in tree order).
    Blocks,
    /// One colour per connected component.
    Components,
    /// Non-manifold vertices, edges and faces, surface boundary edges, inverted cells, on top.
    Defects,
    /// The boundary: surface boundary edges, or the faces opened by the clipping plane.
    Boundary,
    /// One colour per value of the cell attribute [`RenderOptions::attribute`] (its first
    /// component).
    Label,
    /// A colour map of the vertex attribute [`RenderOptions::attribute`] (its first component,
    /// or the length of a vector), faces by the mean of their vertices.
    Field,
}

/// The names accepted by [`ColorMode::from_name`].
pub const COLOR_MODES: &str = "plain blocks components defects boundary label field";

impl ColorMode {
    /// The mode of a name in [`COLOR_MODES`].
    ///
    /// ```
    /// assert!(starplex::render::ColorMode::from_name("defects").is_some());
    /// ```
    pub fn from_name(s: &str) -> Option<ColorMode> {
        Some(match s {
            "plain" => ColorMode::Plain,
            "blocks" => ColorMode::Blocks,
            "components" => ColorMode::Components,
            "defects" => ColorMode::Defects,
            "boundary" => ColorMode::Boundary,
            "label" => ColorMode::Label,
            "field" => ColorMode::Field,
            _ => return None,
        })
    }
    /// Its name.
    ///
    /// ```
    /// assert_eq!(starplex::render::ColorMode::Plain.name(), "plain");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            ColorMode::Plain => "plain",
            ColorMode::Blocks => "blocks",
            ColorMode::Components => "components",
            ColorMode::Defects => "defects",
            ColorMode::Boundary => "boundary",
            ColorMode::Label => "label",
            ColorMode::Field => "field",
        }
    }
}

/// The direction of view (orthographic, z up).
///
/// ```
/// use starplex::render::View;
/// assert_eq!(View::from_name("top"), Some(View::Top));
/// assert_eq!(View::from_name("30,20"), Some(View::Angles { azimuth: 30.0, elevation: 20.0 }));
/// assert_eq!(View::from_name("diagonal"), None);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum View {
    /// From (1, -1, 1): x to the right and towards the viewer, z up.
    Iso,
    /// From -y: x right, z up.
    Front,
    /// From +z: x right, y up.
    Top,
    /// From +x: y right, z up.
    Side,
    /// From azimuth and elevation in degrees (0, 0 is the side view; -90, 0 the front view).
    Angles {
        /// Degrees around z from +x.
        azimuth: f64,
        /// Degrees above the xy plane.
        elevation: f64,
    },
}

impl View {
    /// `iso`, `front`, `top`, `side` or `AZIMUTH,ELEVATION` in degrees.
    ///
    /// ```
    /// assert!(starplex::render::View::from_name("iso").is_some());
    /// ```
    pub fn from_name(s: &str) -> Option<View> {
        Some(match s {
            "iso" => View::Iso,
            "front" => View::Front,
            "top" => View::Top,
            "side" => View::Side,
            _ => {
                let (a, e) = s.split_once(',')?;
                let (azimuth, elevation) = (a.trim().parse().ok()?, e.trim().parse().ok()?);
                if !(f64::is_finite(azimuth) && f64::is_finite(elevation)) {
                    return None;
                }
                View::Angles { azimuth, elevation }
            }
        })
    }
}

/// A clipping plane: top cells whose centroid has coordinate `axis` above `value` are removed,
/// and the faces of the kept 3-cells that the removal exposes are drawn.
///
/// ```
/// use starplex::render::Clip;
/// assert_eq!(Clip::parse("y=0.5"), Some(Clip { axis: 1, value: 0.5 }));
/// assert_eq!(Clip::parse("w=1"), None);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clip {
    /// 0 = x, 1 = y, 2 = z (input coordinates).
    pub axis: usize,
    /// Cells with centroid coordinate at most this are kept.
    pub value: f64,
}

impl Clip {
    /// `x=V`, `y=V` or `z=V`.
    ///
    /// ```
    /// assert!(starplex::render::Clip::parse("z=-1.5").is_some());
    /// ```
    pub fn parse(s: &str) -> Option<Clip> {
        let (a, v) = s.split_once('=')?;
        let axis = match a.trim() {
            "x" | "X" => 0,
            "y" | "Y" => 1,
            "z" | "Z" => 2,
            _ => return None,
        };
        let value: f64 = v.trim().parse().ok()?;
        value.is_finite().then_some(Clip { axis, value })
    }
}

/// A perspective camera: the eye, and the point looked at (`None`: the centre of the bounding
/// box of what is drawn), both in input coordinates. The target lands at the centre of the
/// picture and the field of view is as narrow as can show everything in front of the eye (at
/// most about 127 degrees); what is behind the eye (or within 1/1000 of the target's distance
/// of it) is not drawn.
///
/// ```
/// use starplex::render::Eye;
/// assert_eq!(Eye::parse("1,2,3"), Some(Eye { eye: [1.0, 2.0, 3.0], target: None }));
/// assert_eq!(Eye::parse("0,0,5, 0,0,0").unwrap().target, Some([0.0; 3]));
/// assert_eq!(Eye::parse("1,2"), None);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Eye {
    /// Where the viewer is.
    pub eye: [f64; 3],
    /// What it looks at.
    pub target: Option<[f64; 3]>,
}

impl Eye {
    /// `EX,EY,EZ` or `EX,EY,EZ,TX,TY,TZ` (finite numbers).
    ///
    /// ```
    /// assert!(starplex::render::Eye::parse("1,1,1,0,0,nan").is_none());
    /// ```
    pub fn parse(s: &str) -> Option<Eye> {
        let v: Vec<f64> = s
            .split(',')
            .map(|x| x.trim().parse::<f64>().ok().filter(|x| x.is_finite()))
            .collect::<Option<_>>()?;
        match v.len() {
            3 => Some(Eye {
                eye: [v[0], v[1], v[2]],
                target: None,
            }),
            6 => Some(Eye {
                eye: [v[0], v[1], v[2]],
                target: Some([v[3], v[4], v[5]]),
            }),
            _ => None,
        }
    }
}

/// Options of [`render`] and [`render_svg`].
///
/// ```
/// let o = starplex::render::RenderOptions::default();
/// assert_eq!((o.width, o.height, o.shading, o.smooth, o.legend), (1024, 768, true, false, true));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct RenderOptions {
    /// Picture width in pixels.
    pub width: u32,
    /// Picture height in pixels.
    pub height: u32,
    /// The view (`None`: top for a flat complex, iso otherwise).
    pub view: Option<View>,
    /// Which axis is up (0 = x, 1 = y, 2 = z).
    pub up: usize,
    /// How faces are coloured.
    pub colour: ColorMode,
    /// Draw the edges of the faces.
    pub edges: bool,
    /// Cut the complex open.
    pub clip: Option<Clip>,
    /// Shading by the light (off: every face in its plain colour).
    pub shading: bool,
    /// With `shading`: smooth (Gouraud) shading from per-vertex normals (the area-weighted
    /// mean of the drawn faces' normals, as the faces are oriented) instead of flat shading per
    /// face; corners across a hard edge or between faces oriented against each other (see
    /// [`CREASE_DEGREES`]) stay flat.
    pub smooth: bool,
    /// A perspective camera (replaces `view`).
    pub camera: Option<Eye>,
    /// A box `[low, high]` in input coordinates (the first three) framed as well as what is
    /// drawn: the automatic view, the scale and the camera's default target then come from
    /// both, so that pictures of two complexes with the same frame are to the same scale and
    /// seen the same way (`--compare` frames both sides with the box around both).
    pub frame: Option<[[f64; 3]; 2]>,
    /// First line of the caption (e.g. the file name).
    pub title: Option<String>,
    /// Draw the caption and the legend.
    pub legend: bool,
    /// Bucketing threshold of the Stellar tree for [`ColorMode::Blocks`] (`None`: the default).
    pub kv: Option<u32>,
    /// The attribute of [`ColorMode::Label`] (a cell attribute) and [`ColorMode::Field`] (a
    /// vertex attribute).
    pub attribute: Option<String>,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            width: 1024,
            height: 768,
            view: None,
            up: 2,
            colour: ColorMode::Plain,
            edges: false,
            clip: None,
            shading: true,
            smooth: false,
            camera: None,
            frame: None,
            title: None,
            legend: true,
            kv: None,
            attribute: None,
        }
    }
}

/// The box around the vertices of `ks` in their first three coordinates (a missing coordinate
/// counts as 0, non-finite ones are skipped), for [`RenderOptions::frame`]; `None` when no vertex
/// has a finite coordinate.
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::render::frame_around;
/// let a = IndexedComplex::from_parts(2, vec![0., 0., 1., 0., 0., 1.].into(),
///     vec![(CellKind::Simplex(2), vec![0, 1, 2].into())]).unwrap();
/// let b = IndexedComplex::from_parts(3, vec![5., 5., 5.].into(), vec![]).unwrap();
/// assert_eq!(frame_around(&[&a, &b]), Some([[0.0; 3], [5.0; 3]]));
/// ```
pub fn frame_around(ks: &[&IndexedComplex]) -> Option<[[f64; 3]; 2]> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for k in ks {
        let d = k.ambient_dim();
        if d == 0 {
            continue;
        }
        for c in k.coords().chunks_exact(d) {
            for a in 0..3 {
                let x = if a < d { c[a] } else { 0.0 };
                if x.is_finite() {
                    lo[a] = lo[a].min(x);
                    hi[a] = hi[a].max(x);
                }
            }
        }
    }
    (0..3).all(|a| lo[a] <= hi[a]).then_some([lo, hi])
}

/// Largest accepted width or height.
pub const MAX_SIDE: u32 = 16384;
/// Largest accepted number of pixels.
pub const MAX_PIXELS: u64 = 1 << 26;
/// Memory per pixel while rendering: colour, depth and face id (4 bytes each) and the encoded
/// row (3 bytes).
pub const BYTES_PER_PIXEL: u64 = 15;

/// Why a picture cannot be made.
///
/// ```
/// use starplex::render::{check_size, RenderError};
/// assert!(matches!(check_size(0, 10), Err(RenderError::Size { .. })));
/// ```
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// No vertex at all.
    #[error("the complex is empty: nothing to draw")]
    Empty,
    /// The clipping plane removed everything.
    #[error("the clipping plane removed all {0} top cells: nothing left to draw")]
    NothingLeft(usize),
    /// A size of 0 or too large.
    #[error("picture size {width}x{height}: {reason} (it would need about {} of memory)", human_bytes(*bytes))]
    Size {
        /// Width asked.
        width: u64,
        /// Height asked.
        height: u64,
        /// Memory estimate.
        bytes: u64,
        /// What is wrong.
        reason: String,
    },
    /// The Stellar tree for block colours could not be built.
    #[error("{0}")]
    Stellar(#[from] StellarError),
    /// The camera's eye is its target.
    #[error("the camera's eye is the point it looks at: no direction of view")]
    EyeIsTarget,
    /// `--color label NAME` / `field NAME` with no such attribute.
    #[error("there is no {target} attribute '{name}' to colour by ({})", if available.is_empty() { format!("the file has no {target} attributes") } else { format!("{target} attributes: {}", available.join(", ")) })]
    NoAttribute {
        /// `cell` for labels, `vertex` for fields.
        target: crate::attr::AttrTarget,
        /// The name asked.
        name: String,
        /// The names there are.
        available: Vec<String>,
    },
}

fn human_bytes(b: u64) -> String {
    let b = b as f64;
    if b >= 1e9 {
        format!("{:.1} GB", b / 1e9)
    } else if b >= 1e6 {
        format!("{:.1} MB", b / 1e6)
    } else {
        format!("{:.0} kB", b / 1e3)
    }
}

/// Refuses a size of 0, a side above [`MAX_SIDE`] or more than [`MAX_PIXELS`] pixels, with the
/// memory it would take.
///
/// ```
/// use starplex::render::check_size;
/// assert!(check_size(1600, 1200).is_ok());
/// let e = check_size(100_000, 100_000).unwrap_err().to_string();
/// assert!(e.contains("150.0 GB"), "{e}");
/// ```
///
/// # Errors
/// [`RenderError::Size`].
pub fn check_size(width: u64, height: u64) -> Result<(), RenderError> {
    let bytes = width.saturating_mul(height).saturating_mul(BYTES_PER_PIXEL);
    let reason = if width == 0 || height == 0 {
        "a picture needs at least one pixel each way".to_string()
    } else if width > u64::from(MAX_SIDE) || height > u64::from(MAX_SIDE) {
        format!("at most {MAX_SIDE} pixels each way")
    } else if width * height > MAX_PIXELS {
        format!("at most {MAX_PIXELS} pixels in all")
    } else {
        return Ok(());
    };
    Err(RenderError::Size {
        width,
        height,
        bytes,
        reason,
    })
}

/// What a picture shows, in numbers.
///
/// ```
/// let s = starplex::render::Summary::default();
/// assert_eq!(s.n_faces, 0);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Summary {
    /// Polygons drawn (triangles and quads).
    pub n_faces: usize,
    /// Lines drawn (1-cells).
    pub n_lines: usize,
    /// Dots drawn (0-cells and isolated vertices).
    pub n_points: usize,
    /// Stellar leaves with vertices (blocks) or connected components (components); else 0.
    pub n_colours: usize,
    /// Top cells removed by the clipping plane.
    pub clipped_cells: usize,
    /// Defect counts (defects colouring), as `(what, count)`.
    pub defects: Vec<(String, usize)>,
    /// The caption and legend lines, with their swatch colour (0xRRGGBB) if any.
    pub legend: Vec<(Option<u32>, String)>,
    /// What was changed to draw it (projection of higher dimensions, ...).
    pub notes: Vec<String>,
    /// The colour bar of a field (field colouring).
    pub colour_bar: Option<ColourBar>,
}

/// The colour bar of [`ColorMode::Field`]: the ramp from `lo` (left end) to `hi` (right end),
/// drawn in the legend at `rect` (pixels, `[x0, y0, x1, y1)`; `None` without a legend), with
/// both ends labelled.
///
/// ```
/// let b = starplex::render::ColourBar { name: "t".into(), lo: 0.0, hi: 1.0, rect: None };
/// assert!(b.lo < b.hi);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ColourBar {
    /// The attribute.
    pub name: String,
    /// The smallest finite value (the left end).
    pub lo: f64,
    /// The largest finite value (the right end).
    pub hi: f64,
    /// Where it is drawn.
    pub rect: Option<[usize; 4]>,
}

/// Results computed elsewhere that a picture can reuse instead of computing them again (the
/// `--render` shortcuts of `validate` and `stellar`). They must be of the same complex: the
/// validation of [`ColorMode::Defects`], the Stellar tree of [`ColorMode::Blocks`].
///
/// ```
/// let g = starplex::render::Given::default();
/// assert!(g.validation.is_none() && g.tree.is_none());
/// ```
#[derive(Clone, Copy, Default)]
pub struct Given<'a> {
    /// `validate` of the complex (input vertex ids).
    pub validation: Option<&'a crate::algo::validate::ValidationReport>,
    /// A Stellar tree of the complex.
    pub tree: Option<&'a StellarTree>,
}

/// A rendered picture: RGB pixels row by row from the top.
///
/// ```
/// # use starplex::cell::CellKind;
/// # use starplex::complex::IndexedComplex;
/// use starplex::render::{render, RenderOptions};
/// # let k = IndexedComplex::from_parts(2, vec![0., 0., 1., 0., 0., 1.].into(),
/// #     vec![(CellKind::Simplex(2), vec![0, 1, 2].into())]).unwrap();
/// let pic = render(&k, &RenderOptions { width: 64, height: 48, ..Default::default() }).unwrap();
/// assert_eq!((pic.width, pic.height, pic.pixels.len()), (64, 48, 64 * 48));
/// assert_eq!(pic.rgb().len(), 64 * 48 * 3);
/// ```
#[derive(Clone, Debug)]
pub struct Picture {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// 0xRRGGBB per pixel.
    pub pixels: Vec<u32>,
    /// What it shows.
    pub summary: Summary,
    camera: Camera,
    up: usize,
    x_offset: f64,
}

impl Picture {
    /// The colour at (x, y) (0xRRGGBB); white outside.
    ///
    /// ```
    /// # use starplex::cell::CellKind;
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::render::{render, RenderOptions};
    /// # let k = IndexedComplex::from_parts(2, vec![0., 0., 1., 0., 0., 1.].into(),
    /// #     vec![(CellKind::Simplex(2), vec![0, 1, 2].into())]).unwrap();
    /// let pic = render(&k, &RenderOptions { width: 64, height: 48, ..Default::default() }).unwrap();
    /// assert_eq!(pic.pixel(1000, 0), 0xFFFFFF);
    /// ```
    pub fn pixel(&self, x: usize, y: usize) -> u32 {
        if x < self.width && y < self.height {
            self.pixels[y * self.width + x]
        } else {
            colour::BACKGROUND
        }
    }

    /// Where a point (input coordinates) lands in the picture (pixels, y down).
    ///
    /// ```
    /// # use starplex::cell::CellKind;
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::render::{render, RenderOptions, View};
    /// # let k = IndexedComplex::from_parts(2, vec![0., 0., 1., 0., 0., 1.].into(),
    /// #     vec![(CellKind::Simplex(2), vec![0, 1, 2].into())]).unwrap();
    /// let o = RenderOptions { width: 100, height: 100, view: Some(View::Top), legend: false, ..Default::default() };
    /// let pic = render(&k, &o).unwrap();
    /// let (x0, y0) = pic.project(&[0.0, 0.0]);
    /// let (x1, y1) = pic.project(&[1.0, 0.0]);
    /// assert!(x1 > x0 && (y1 - y0).abs() < 1e-9);
    /// ```
    pub fn project(&self, p: &[f64]) -> (f64, f64) {
        let g = |a: usize| p.get(a).copied().unwrap_or(0.0);
        let s = self
            .camera
            .project(scene::turn([g(0), g(1), g(2)], self.up));
        (s[0] + self.x_offset, s[1])
    }

    /// The pixels as RGB bytes.
    ///
    /// ```
    /// # use starplex::cell::CellKind;
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::render::{render, RenderOptions};
    /// # let k = IndexedComplex::from_parts(2, vec![0., 0., 1., 0., 0., 1.].into(),
    /// #     vec![(CellKind::Simplex(2), vec![0, 1, 2].into())]).unwrap();
    /// let pic = render(&k, &RenderOptions { width: 8, height: 8, ..Default::default() }).unwrap();
    /// assert_eq!(pic.rgb()[..3], [255, 255, 255]); // a background corner
    /// ```
    pub fn rgb(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.pixels.len() * 3);
        for &p in &self.pixels {
            out.extend_from_slice(&[(p >> 16) as u8, (p >> 8) as u8, p as u8]);
        }
        out
    }

    /// Two pictures side by side (`self` left), with a one-pixel separator; [`Picture::project`]
    /// then answers for the left one.
    ///
    /// ```
    /// # use starplex::cell::CellKind;
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::render::{render, RenderOptions};
    /// # let k = IndexedComplex::from_parts(2, vec![0., 0., 1., 0., 0., 1.].into(),
    /// #     vec![(CellKind::Simplex(2), vec![0, 1, 2].into())]).unwrap();
    /// let a = render(&k, &RenderOptions { width: 30, height: 20, ..Default::default() }).unwrap();
    /// let b = render(&k, &RenderOptions { width: 40, height: 25, ..Default::default() }).unwrap();
    /// let ab = a.beside(&b);
    /// assert_eq!((ab.width, ab.height), (71, 25));
    /// ```
    pub fn beside(&self, other: &Picture) -> Picture {
        let (w, h) = (self.width + 1 + other.width, self.height.max(other.height));
        let mut pixels = vec![colour::BACKGROUND; w * h];
        for y in 0..h {
            for x in 0..w {
                pixels[y * w + x] = if x < self.width {
                    self.pixel(x, y)
                } else if x == self.width {
                    0x80_80_80
                } else {
                    other.pixel(x - self.width - 1, y)
                };
            }
        }
        let mut summary = self.summary.clone();
        summary.notes.extend(other.summary.notes.iter().cloned());
        Picture {
            width: w,
            height: h,
            pixels,
            summary,
            camera: self.camera.clone(),
            up: self.up,
            x_offset: self.x_offset,
        }
    }
}

/// A defect marker.
enum Marker {
    /// At a vertex.
    Vertex(u32, u32),
    /// At a point (a cell centroid).
    At([f64; 3], u32),
    /// Along an edge, this thick.
    Edge([u32; 2], u32, usize),
}

/// Everything decided before drawing.
struct Prepared {
    scene: Scene,
    cam: Camera,
    face_colour: Vec<u32>,
    line_colour: Vec<u32>,
    point_colour: Vec<u32>,
    markers: Vec<Marker>,
    /// Per-vertex colours of the faces (field colouring): the faces are coloured between their
    /// corners instead of by `face_colour`.
    vertex_base: Option<Vec<u32>>,
    summary: Summary,
    text_scale: usize,
    caption_rows: usize,
}

/// The view when none is given: top for a complex flat in z, iso otherwise.
fn auto_view(pos: &[[f64; 3]]) -> View {
    let flat = pos.windows(2).all(|w| w[0][2] == w[1][2]);
    if flat {
        View::Top
    } else {
        View::Iso
    }
}

fn thousands(n: usize) -> String {
    let s = n.to_string();
    let mut out = String::new();
    for (i, ch) in s.chars().enumerate() {
        if i > 0 && (s.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(ch);
    }
    out
}

/// A short label of a number for the legend (at most about 5 significant digits).
fn short(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let a = x.abs();
    if !(1e-3..1e6).contains(&a) {
        return format!("{x:.3e}");
    }
    let decimals = (4 - a.log10().floor() as i64).clamp(0, 6) as usize;
    let t = format!("{x:.decimals$}");
    if t.contains('.') {
        t.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        t
    }
}

fn prepare(k: &IndexedComplex, o: &RenderOptions, given: Given) -> Result<Prepared, RenderError> {
    check_size(u64::from(o.width), u64::from(o.height))?;
    if k.n_vertices() == 0 {
        return Err(RenderError::Empty);
    }
    let scene = scene::build(k, o.clip, o.up, o.colour == ColorMode::Boundary);
    if scene.faces.is_empty() && scene.lines.is_empty() && scene.points.is_empty() {
        return Err(RenderError::NothingLeft(scene.clipped_cells));
    }
    let mut summary = Summary {
        n_faces: scene.faces.len(),
        n_lines: scene.lines.len(),
        n_points: scene.points.len(),
        clipped_cells: scene.clipped_cells,
        notes: scene.notes.clone(),
        ..Default::default()
    };
    let mut caption: Vec<(Option<u32>, String)> = Vec::new();
    if let Some(t) = &o.title {
        caption.push((None, t.clone()));
    }
    let dim = k.dim().map_or("-".to_string(), |d| d.to_string());
    caption.push((
        None,
        format!(
            "{} vertices, {} cells, dimension {dim}{}",
            thousands(k.n_vertices()),
            thousands(k.n_cells()),
            if scene.clipped_cells > 0 {
                format!(", {} cut away", thousands(scene.clipped_cells))
            } else {
                String::new()
            }
        ),
    ));

    let paint::Paint {
        cell_colour,
        vertex_colour,
        vertex_base,
        markers,
        legend,
    } = paint::paint(k, o, &given, &scene, &mut summary)?;
    caption.extend(legend);
    let text_scale = ((f64::from(o.height.min(o.width * 3 / 4)) / 400.0).round() as usize).max(1);
    let lh = font::line_height(text_scale) as f64;
    let caption_rows = if o.legend { caption.len() } else { 0 };
    let bar_rows = usize::from(o.legend && summary.colour_bar.is_some());
    if let (Some(bar), true) = (summary.colour_bar.as_mut(), o.legend) {
        bar.rect = Some(bar_rect(
            o.width as usize,
            o.height as usize,
            text_scale,
            caption_rows,
        ));
    }
    summary.legend = caption;
    let (w, h) = (f64::from(o.width), f64::from(o.height));
    let margin = (0.04 * w.min(h)).max(2.0);
    let top = margin
        + if o.legend {
            lh * (caption_rows + bar_rows) as f64
        } else {
            0.0
        };
    let mut rect = [margin, top, w - margin, h - margin];
    if rect[3] - rect[1] < 0.3 * h {
        rect = [margin, margin, w - margin, h - margin]; // too small for the caption: overlap
    }
    let cam = place_camera(o, &scene, rect)?;
    let face_colour = scene
        .faces
        .iter()
        .map(|f| {
            if o.colour == ColorMode::Boundary && f.exposed {
                colour::EXPOSED
            } else {
                cell_colour[f.cell as usize]
            }
        })
        .collect();
    let plain_lines = o.colour == ColorMode::Plain || o.colour == ColorMode::Defects;
    let line_colour = scene
        .lines
        .iter()
        .map(|&(c, _)| {
            if plain_lines {
                colour::LINE
            } else {
                cell_colour[c as usize]
            }
        })
        .collect();
    let point_colour = scene
        .points
        .iter()
        .map(|&(c, v)| match (&vertex_colour, c) {
            (Some(vc), NO_CELL) => vc[v as usize],
            (_, NO_CELL) => colour::LINE,
            _ if plain_lines => colour::LINE,
            _ => cell_colour[c as usize],
        })
        .collect();
    Ok(Prepared {
        scene,
        cam,
        face_colour,
        line_colour,
        point_colour,
        markers,
        vertex_base,
        summary,
        text_scale,
        caption_rows,
    })
}

/// The camera: `o.camera` aimed at its target (the middle of what is drawn by default), or a
/// view (`o.view`, else one chosen from the drawn points) fitted to `rect`; `o.frame`'s corners
/// count as drawn.
fn place_camera(
    o: &RenderOptions,
    scene: &scene::Scene,
    rect: [f64; 4],
) -> Result<Camera, RenderError> {
    let used = scene.used();
    let corners: Vec<[f64; 3]> = o.frame.map_or_else(Vec::new, |[lo, hi]| {
        (0..8)
            .map(|i| {
                let c = [0, 1, 2].map(|a| if i >> a & 1 == 0 { lo[a] } else { hi[a] });
                scene::turn(c, o.up)
            })
            .filter(|c| c.iter().all(|x| x.is_finite()))
            .collect()
    });
    let view = o.view.unwrap_or_else(|| {
        let pts: Vec<[f64; 3]> = if corners.is_empty() {
            used.iter().map(|&v| scene.pos[v as usize]).collect()
        } else {
            corners.clone()
        };
        auto_view(&pts)
    });
    let drawn = used
        .iter()
        .map(|&v| scene.pos[v as usize])
        .chain(corners.iter().copied());
    match o.camera {
        None => Ok(Camera::fit(view, drawn, rect)),
        Some(e) => {
            let turn = |p: [f64; 3]| scene::turn(p, o.up);
            let target = e.target.map(turn).unwrap_or_else(|| {
                let mut lo = [f64::INFINITY; 3];
                let mut hi = [f64::NEG_INFINITY; 3];
                for p in drawn.clone() {
                    for a in 0..3 {
                        lo[a] = lo[a].min(p[a]);
                        hi[a] = hi[a].max(p[a]);
                    }
                }
                [0, 1, 2].map(|a| 0.5 * (lo[a] + hi[a]))
            });
            let eye = turn(e.eye);
            if eye == target {
                return Err(RenderError::EyeIsTarget);
            }
            Ok(Camera::look_at(eye, target, drawn, rect))
        }
    }
}

/// Where the colour bar goes: the legend row after the `row` caption lines, room for the low
/// label on its left and the high label on its right.
fn bar_rect(w: usize, h: usize, ts: usize, row: usize) -> [usize; 4] {
    let x0 = (0.02 * w.min(h) as f64).max(2.0) as usize;
    let y = x0 + row * font::line_height(ts);
    let label = 11 * 6 * ts; // room for a label of 10 characters and a space
    let len = (w / 3)
        .max(40 * ts)
        .min(w.saturating_sub(2 * x0 + 2 * label).max(8));
    [x0 + label, y, x0 + label + len, y + 7 * ts]
}

/// Light direction in view coordinates (mostly from the viewer, a little from the upper left).
const LIGHT: [f64; 3] = [-0.25, 0.35, 0.9];

/// The normal of a face (a triangle's, or a quad's from the cross product of its diagonals),
/// in view coordinates, length twice the area (of a triangle).
fn face_normal(p: &Prepared, vs: &[u32]) -> [f64; 3] {
    let q = |i: usize| p.scene.pos[vs[i] as usize];
    let (a, b, c3) = (q(0), q(1), q(2));
    let (u, w) = if vs.len() == 4 {
        let d = q(3);
        (
            [c3[0] - a[0], c3[1] - a[1], c3[2] - a[2]],
            [d[0] - b[0], d[1] - b[1], d[2] - b[2]],
        )
    } else {
        (
            [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
            [c3[0] - a[0], c3[1] - a[1], c3[2] - a[2]],
        )
    };
    p.cam.rotate([
        u[1] * w[2] - u[2] * w[1],
        u[2] * w[0] - u[0] * w[2],
        u[0] * w[1] - u[1] * w[0],
    ])
}

/// The light's intensity on a surface of normal `nv` (view coordinates, any length, either
/// side lit).
fn intensity(nv: [f64; 3], l: [f64; 3]) -> f32 {
    let len = (nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]).sqrt();
    let d = if len > 0.0 {
        ((nv[0] * l[0] + nv[1] * l[1] + nv[2] * l[2]) / len).abs()
    } else {
        0.0
    };
    (0.3 + 0.7 * d) as f32
}

/// How the faces are lit: per face (flat), per vertex (smooth) or not at all.
enum Lit {
    Off,
    Face(Vec<f32>),
    /// Smooth: per face its flat intensity and unit normal, per vertex its unit normal and
    /// intensity (`[nx, ny, nz, intensity]`); a corner whose face normal is more than
    /// [`CREASE_DEGREES`] from its vertex normal is lit flat (a hard edge stays sharp).
    Vertex {
        face: Vec<f32>,
        face_normal: Vec<[f32; 3]>,
        vertex: Vec<[f32; 4]>,
        /// cos([`CREASE_DEGREES`]).
        crease: f32,
    },
}

/// Smooth shading: a face corner whose face normal turns more than this from the vertex
/// normal (the area-weighted mean of its faces') is lit by the face normal instead, so that
/// two faces meeting at a dihedral angle of more than about twice this keep a sharp edge (a
/// box stays a box) while finely curved surfaces are smooth.
///
/// ```
/// // the corner of a cube: its three faces are 54.7 degrees from the mean normal, lit flat
/// let to_mean = (1.0f64 / 3.0f64.sqrt()).acos().to_degrees();
/// assert!(to_mean > starplex::render::CREASE_DEGREES);
/// ```
pub const CREASE_DEGREES: f64 = 30.0;

fn unit(n: [f64; 3]) -> [f64; 3] {
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len > 0.0 {
        n.map(|x| x / len)
    } else {
        [0.0; 3]
    }
}

fn lighting(p: &Prepared, o: &RenderOptions) -> Lit {
    if !o.shading {
        return Lit::Off;
    }
    let l = unit(LIGHT);
    if !o.smooth {
        return Lit::Face(
            p.scene
                .faces
                .iter()
                .map(|f| intensity(face_normal(p, f.verts()), l))
                .collect(),
        );
    }
    // per-vertex normals: area-weighted sums of the face normals as the faces are oriented
    // (a volume's boundary faces as induced by their cells); where neighbouring faces are
    // oriented against each other the sum turns away from both and the crease rule lights
    // them flat
    let mut nrm = vec![[0.0f64; 3]; p.scene.pos.len()];
    let mut face = Vec::with_capacity(p.scene.faces.len());
    let mut face_normal_unit = Vec::with_capacity(p.scene.faces.len());
    for f in &p.scene.faces {
        let vs = f.verts();
        let n = face_normal(p, vs);
        for &v in vs {
            for (s, x) in nrm[v as usize].iter_mut().zip(n) {
                *s += x;
            }
        }
        face.push(intensity(n, l));
        face_normal_unit.push(unit(n).map(|x| x as f32));
    }
    let vertex = nrm
        .into_iter()
        .map(|n| {
            let u = unit(n);
            [u[0] as f32, u[1] as f32, u[2] as f32, intensity(n, l)]
        })
        .collect();
    Lit::Vertex {
        face,
        face_normal: face_normal_unit,
        vertex,
        crease: CREASE_DEGREES.to_radians().cos() as f32,
    }
}

/// The colours of the corners of face `i` (the first `n` of them), lit.
fn corner_colours(p: &Prepared, lit: &Lit, i: usize) -> [u32; 4] {
    let f = &p.scene.faces[i];
    let mut out = [0u32; 4];
    for (j, &v) in f.verts().iter().enumerate() {
        let base = p
            .vertex_base
            .as_ref()
            .map_or(p.face_colour[i], |b| b[v as usize]);
        out[j] = match lit {
            Lit::Off => base,
            Lit::Face(fi) => colour::shade(base, fi[i]),
            Lit::Vertex {
                face,
                face_normal,
                vertex,
                crease,
            } => {
                let (nf, q) = (face_normal[i], vertex[v as usize]);
                let along = nf[0] * q[0] + nf[1] * q[1] + nf[2] * q[2];
                colour::shade(base, if along >= *crease { q[3] } else { face[i] })
            }
        };
    }
    out
}

/// One colour per face (the mean of its lit corners), for SVG.
fn shaded_colours(p: &Prepared, o: &RenderOptions) -> Vec<u32> {
    let lit = lighting(p, o);
    (0..p.scene.faces.len())
        .map(|i| {
            let n = p.scene.faces[i].verts().len();
            colour::mean(&corner_colours(p, &lit, i)[..n])
        })
        .collect()
}

/// Draws the prepared scene. `order`: the order in which faces are drawn (default: as stored).
fn draw(p: &Prepared, o: &RenderOptions, order: Option<&[u32]>) -> Canvas {
    let (w, h) = (o.width as usize, o.height as usize);
    let mut cv = Canvas::new(w, h, colour::BACKGROUND);
    let proj: Vec<[f32; 3]> = p
        .scene
        .pos
        .iter()
        .map(|&q| p.cam.project(q).map(|x| x as f32))
        .collect();
    let lit = lighting(p, o);
    let mut draw_face = |i: usize| {
        let f = &p.scene.faces[i];
        let v = f.verts();
        let (a, b, c) = (
            proj[v[0] as usize],
            proj[v[1] as usize],
            proj[v[2] as usize],
        );
        let k = corner_colours(p, &lit, i);
        cv.triangle_colours(a, b, c, [k[0], k[1], k[2]], i as u32);
        if v.len() == 4 {
            cv.triangle_colours(a, c, proj[v[3] as usize], [k[0], k[2], k[3]], i as u32);
        }
    };
    match order {
        Some(ord) => ord.iter().for_each(|&i| draw_face(i as usize)),
        None => (0..p.scene.faces.len()).for_each(draw_face),
    }
    let unit = (w.min(h) as f32 / 600.0).max(1.0);
    let bias = Some(1.5 * unit);
    for (&(_, e), &c) in p.scene.lines.iter().zip(&p.line_colour) {
        cv.line(
            proj[e[0] as usize],
            proj[e[1] as usize],
            c,
            unit.round() as usize,
            bias,
        );
    }
    for (&(_, v), &c) in p.scene.points.iter().zip(&p.point_colour) {
        cv.dot(proj[v as usize], 1.5 * unit, c, None, bias);
    }
    if o.edges {
        for f in &p.scene.faces {
            let v = f.verts();
            for i in 0..v.len() {
                let (a, b) = (v[i], v[(i + 1) % v.len()]);
                cv.line(proj[a as usize], proj[b as usize], colour::WIRE, 1, bias);
            }
        }
    }
    // markers on top: edges first, then dots
    let r = (w.min(h) as f32 / 120.0).max(5.0);
    for m in &p.markers {
        if let Marker::Edge(e, c, t) = m {
            let t = (*t as f32 * unit * 0.75).round().max(*t as f32) as usize;
            cv.line(proj[e[0] as usize], proj[e[1] as usize], *c, t, None);
        }
    }
    for m in &p.markers {
        match m {
            Marker::Vertex(v, c) => cv.dot(proj[*v as usize], r, *c, Some(colour::OUTLINE), None),
            Marker::At(q, c) => {
                let s = p.cam.project(*q).map(|x| x as f32);
                cv.dot(s, 0.6 * r, *c, Some(colour::OUTLINE), None);
            }
            Marker::Edge(..) => {}
        }
    }
    if o.legend {
        let ts = p.text_scale;
        let lh = font::line_height(ts) as i64;
        let x0 = (0.02 * w.min(h) as f64).max(2.0) as i64;
        let mut y = x0;
        for (sw, text) in p.summary.legend.iter().take(p.caption_rows) {
            let mut x = x0;
            if let Some(c) = sw {
                let s = 7 * ts as i64;
                cv.rect(x - 1, y - 1, x + s + 1, y + s + 1, colour::OUTLINE);
                cv.rect(x, y, x + s, y + s, *c);
                x += s + 3 * ts as i64;
            }
            font::draw_text(&mut cv, x, y, text, colour::INK, ts);
            y += lh;
        }
        if let Some(ColourBar {
            lo,
            hi,
            rect: Some(r),
            ..
        }) = &p.summary.colour_bar
        {
            let [x0, y0, x1, y1] = r.map(|v| v as i64);
            cv.rect(x0 - 1, y0 - 1, x1 + 1, y1 + 1, colour::OUTLINE);
            for x in x0..x1 {
                let t = (x - x0) as f64 / (x1 - x0 - 1).max(1) as f64;
                cv.rect(x, y0, x + 1, y1, colour::ramp(t));
            }
            let (l, h) = (short(*lo), short(*hi));
            let adv = 6 * ts as i64;
            font::draw_text(
                &mut cv,
                x0 - adv * (l.chars().count() as i64 + 1),
                y0,
                &l,
                colour::INK,
                ts,
            );
            font::draw_text(&mut cv, x1 + adv, y0, &h, colour::INK, ts);
        }
    }
    cv
}

/// Renders `k` to pixels.
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::render::{render, RenderOptions, ColorMode};
/// let k = IndexedComplex::from_parts(3,
///     vec![0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1.].into(),
///     vec![(CellKind::Simplex(3), vec![0, 1, 2, 3].into())]).unwrap();
/// let o = RenderOptions { width: 200, height: 150, colour: ColorMode::Defects, ..Default::default() };
/// let pic = render(&k, &o).unwrap();
/// assert_eq!(pic.summary.n_faces, 4); // the boundary of the tetrahedron
/// ```
///
/// # Errors
/// [`RenderError`]: a bad size, an empty complex, everything clipped away, a failed Stellar
/// tree.
pub fn render(k: &IndexedComplex, o: &RenderOptions) -> Result<Picture, RenderError> {
    render_with(k, o, Given::default())
}

/// As [`render`], reusing results already computed (a validation, a Stellar tree).
///
/// ```
/// use starplex::algo::validate::validate;
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::render::{render_with, ColorMode, Given, RenderOptions};
/// use starplex::topo::naive::VtIndex;
/// let k = IndexedComplex::from_parts(2, vec![0., 0., 1., 0., 0., 1.].into(),
///     vec![(CellKind::Simplex(2), vec![0, 1, 2].into())]).unwrap();
/// let r = validate(&VtIndex::new(&k));
/// let o = RenderOptions { width: 80, height: 60, colour: ColorMode::Defects, ..Default::default() };
/// let pic = render_with(&k, &o, Given { validation: Some(&r), ..Default::default() }).unwrap();
/// assert!(pic.summary.defects.contains(&("boundary edges".to_string(), 3)));
/// ```
///
/// # Errors
/// As [`render`].
pub fn render_with(
    k: &IndexedComplex,
    o: &RenderOptions,
    given: Given,
) -> Result<Picture, RenderError> {
    let p = prepare(k, o, given)?;
    let cv = draw(&p, o, None);
    Ok(Picture {
        width: cv.w,
        height: cv.h,
        pixels: cv.px,
        summary: p.summary,
        camera: p.cam,
        up: o.up,
        x_offset: 0.0,
    })
}

/// Renders `k` as an SVG document: one `<path>` per visible face (in `<g id="faces">`, back to
/// front), lines, dots, defect markers and the caption. Visible faces are those owning pixels
/// of the depth-buffered picture of the same size (at least 3, or a quarter of their own
/// area), so it is meant for small meshes.
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::render::{render_svg, RenderOptions};
/// let k = IndexedComplex::from_parts(2, vec![0., 0., 1., 0., 0., 1.].into(),
///     vec![(CellKind::Simplex(2), vec![0, 1, 2].into())]).unwrap();
/// let (svg, _) = render_svg(&k, &RenderOptions::default()).unwrap();
/// assert!(svg.starts_with("<?xml") && svg.matches("<path").count() >= 1);
/// ```
///
/// # Errors
/// As [`render`].
pub fn render_svg(k: &IndexedComplex, o: &RenderOptions) -> Result<(String, Summary), RenderError> {
    render_svg_with(k, o, Given::default())
}

/// As [`render_svg`], reusing results already computed (a validation, a Stellar tree).
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::render::{render_svg_with, Given, RenderOptions};
/// let k = IndexedComplex::from_parts(2, vec![0., 0., 1., 0., 0., 1.].into(),
///     vec![(CellKind::Simplex(2), vec![0, 1, 2].into())]).unwrap();
/// let (svg, _) = render_svg_with(&k, &RenderOptions::default(), Given::default()).unwrap();
/// assert!(svg.contains("<path"));
/// ```
///
/// # Errors
/// As [`render`].
pub fn render_svg_with(
    k: &IndexedComplex,
    o: &RenderOptions,
    given: Given,
) -> Result<(String, Summary), RenderError> {
    let p = prepare(k, o, given)?;
    // nearest first, so that ties along shared edges go to the nearer face
    let depth: Vec<f64> = p
        .scene
        .faces
        .iter()
        .map(|f| {
            let v = f.verts();
            v.iter()
                .map(|&x| p.cam.project(p.scene.pos[x as usize])[2])
                .sum::<f64>()
                / v.len() as f64
        })
        .collect();
    let mut order: Vec<u32> = (0..p.scene.faces.len() as u32).collect();
    order.sort_by(|&a, &b| depth[b as usize].total_cmp(&depth[a as usize]));
    let cv = draw(&p, o, Some(&order));
    let mut owned = vec![0usize; p.scene.faces.len()];
    for &f in &cv.face {
        if f != NO_FACE {
            owned[f as usize] += 1;
        }
    }
    let visible: Vec<u32> = order
        .iter()
        .rev()
        .copied()
        .filter(|&i| {
            let f = &p.scene.faces[i as usize];
            let area = svg::projected_area(f.verts(), &p.scene.pos, &p.cam);
            let n = owned[i as usize];
            n >= 3 || (n > 0 && n as f64 >= 0.25 * area)
        })
        .collect();
    let cols = shaded_colours(&p, o);
    let doc = svg::document(&p, o, &visible, &cols);
    Ok((doc, p.summary))
}

/// Encodes a picture as PNG (RGB, 8 bits, fast compression).
///
/// ```
/// # use starplex::cell::CellKind;
/// # use starplex::complex::IndexedComplex;
/// use starplex::render::{render, write_png, RenderOptions};
/// # let k = IndexedComplex::from_parts(2, vec![0., 0., 1., 0., 0., 1.].into(),
/// #     vec![(CellKind::Simplex(2), vec![0, 1, 2].into())]).unwrap();
/// let pic = render(&k, &RenderOptions { width: 32, height: 32, ..Default::default() }).unwrap();
/// let mut bytes = Vec::new();
/// write_png(&pic, &mut bytes).unwrap();
/// assert_eq!(&bytes[1..4], b"PNG");
/// ```
///
/// # Errors
/// The writer's error, or the encoder's.
#[cfg(feature = "render")]
pub fn write_png(pic: &Picture, w: &mut dyn std::io::Write) -> Result<(), crate::io::IoErrorKind> {
    let mut e = png::Encoder::new(w, pic.width as u32, pic.height as u32);
    e.set_color(png::ColorType::Rgb);
    e.set_depth(png::BitDepth::Eight);
    e.set_compression(png::Compression::Fast);
    let err = |x: png::EncodingError| match x {
        png::EncodingError::IoError(e) => crate::io::IoErrorKind::Os(e),
        other => crate::io::IoErrorKind::Parse(format!("PNG: {other}")),
    };
    let mut wr = e.write_header().map_err(err)?;
    wr.write_image_data(&pic.rgb()).map_err(err)?;
    wr.finish().map_err(err)?;
    Ok(())
}
