//! `starplex render FILE -o OUT.png|OUT.svg [--color MODE] [--view V | --camera EYE[,TARGET]]
//! [--shading flat|smooth|none] [--size WxH] [--edges] [--clip AXIS=VALUE] [--compare OTHER]`:
//! a picture of the complex, headless.
use std::path::{Path, PathBuf};
use std::time::Instant;

use starplex::complex::IndexedComplex;
use starplex::io::output;
use starplex::render::{self, Clip, ColorMode, Eye, Given, RenderOptions, View, COLOR_MODES};

use crate::common::{self, CliError, Ctx, InputArgs};

#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub input: InputArgs,
    /// Output picture: OUT.png or OUT.svg (SVG: one path per visible face, for small meshes).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Colouring: plain, blocks (Stellar tree leaves), components, defects (from validate,
    /// drawn on top), boundary, `label NAME` (a cell attribute, one colour per value), `field
    /// NAME` (a vertex attribute, a colour ramp; vectors by their length).
    #[arg(long = "color", alias = "colour", num_args = 1..=2, value_names = ["MODE", "NAME"], default_value = "plain")]
    pub color: Vec<String>,
    /// View: iso, front (from -y), top (from +z), side (from +x), or AZIMUTH,ELEVATION in
    /// degrees (default: top for a flat mesh, iso otherwise).
    #[arg(long, allow_hyphen_values = true)]
    pub view: Option<String>,
    /// A perspective camera instead of --view: the eye EX,EY,EZ and optionally the point looked
    /// at TX,TY,TZ (default: the centre of the bounding box), in the file's coordinates. The
    /// target is at the centre of the picture; the field of view is the narrowest that shows
    /// everything in front of the eye; what is behind the eye is not drawn.
    #[arg(
        long,
        value_name = "EX,EY,EZ[,TX,TY,TZ]",
        allow_hyphen_values = true,
        conflicts_with = "view"
    )]
    pub camera: Option<String>,
    /// The axis that is up: x, y or z.
    #[arg(long, default_value = "z")]
    pub up: String,
    /// Picture size WIDTHxHEIGHT in pixels.
    #[arg(long, default_value = "1600x1200")]
    pub size: String,
    /// Draw the edges of the faces (wireframe over the shaded faces).
    #[arg(long)]
    pub edges: bool,
    /// Cut the mesh open: keep the top cells whose centroid has AXIS <= VALUE (e.g. x=0.5) and
    /// show the faces of the kept volume cells that the cut exposes.
    #[arg(long, value_name = "AXIS=VALUE", allow_hyphen_values = true)]
    pub clip: Option<String>,
    /// Shading: flat (one light value per face), smooth (Gouraud: per-vertex normals, the
    /// area-weighted mean of the faces' normals, interpolated colours; edges sharper than
    /// about 60 degrees stay sharp) or none.
    #[arg(long, default_value = "flat", value_parser = ["flat", "smooth", "none"])]
    pub shading: String,
    /// No shading (the same as --shading none).
    #[arg(long)]
    pub no_shading: bool,
    /// No caption and legend.
    #[arg(long)]
    pub no_legend: bool,
    /// Caption title (default: the file name).
    #[arg(long)]
    pub title: Option<String>,
    /// Bucketing threshold of the Stellar tree for --color blocks.
    #[arg(long)]
    pub kv: Option<u32>,
    /// Render another file (e.g. the output of `simplify`) beside this one, with the same
    /// options (PNG only).
    #[arg(long, value_name = "OTHER")]
    pub compare: Option<PathBuf>,
}

fn bad(msg: String, hint: Option<String>) -> CliError {
    CliError::Input(msg, hint)
}

/// `--color` to a mode, with the attribute name of `label NAME` / `field NAME`.
pub fn colour_mode(args: &[String]) -> Result<(ColorMode, Option<String>), CliError> {
    let name = args.first().map(String::as_str).unwrap_or("plain");
    let m = ColorMode::from_name(name).ok_or_else(|| {
        bad(
            format!("--color {name}: unknown colour mode"),
            Some(format!("colour modes: {COLOR_MODES} (label NAME: a cell attribute, field NAME: a vertex attribute)")),
        )
    })?;
    let needs_name = matches!(m, ColorMode::Label | ColorMode::Field);
    match (needs_name, args.get(1)) {
        (true, None) => Err(bad(
            format!("--color {name} needs the attribute's name: --color {name} NAME"),
            Some("`starplex info FILE` lists the attributes of a file".into()),
        )),
        (false, Some(extra)) => Err(bad(
            format!("--color {name} takes no name (got '{extra}')"),
            None,
        )),
        (_, n) => Ok((m, n.cloned())),
    }
}

/// `WxH`.
pub fn parse_size(s: &str) -> Result<(u32, u32), CliError> {
    let err = || {
        bad(
            format!("--size {s}: expected WIDTHxHEIGHT in pixels, e.g. 1600x1200"),
            None,
        )
    };
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(err)?;
    let (w, h): (u64, u64) = (
        w.trim().parse().map_err(|_| err())?,
        h.trim().parse().map_err(|_| err())?,
    );
    render::check_size(w, h).map_err(|e| bad(format!("--size {s}: {e}"), None))?;
    Ok((w as u32, h as u32))
}

/// The options of the render flags (shared with the `--render` shortcuts).
pub fn options(a: &RenderArgs, title: String) -> Result<RenderOptions, CliError> {
    let (colour, attribute) = colour_mode(&a.color)?;
    let (width, height) = parse_size(&a.size)?;
    let view = match &a.view {
        None => None,
        Some(v) => Some(View::from_name(v).ok_or_else(|| {
            bad(
                format!("--view {v}: unknown view"),
                Some("views: iso, front, top, side, or AZIMUTH,ELEVATION in degrees".into()),
            )
        })?),
    };
    let up = match a.up.as_str() {
        "x" | "X" => 0,
        "y" | "Y" => 1,
        "z" | "Z" => 2,
        u => return Err(bad(format!("--up {u}: expected x, y or z"), None)),
    };
    let camera = match &a.camera {
        None => None,
        Some(c) => Some(Eye::parse(c).ok_or_else(|| {
            bad(
                format!("--camera {c}: expected EX,EY,EZ or EX,EY,EZ,TX,TY,TZ (finite numbers)"),
                None,
            )
        })?),
    };
    let clip = match &a.clip {
        None => None,
        Some(c) => Some(Clip::parse(c).ok_or_else(|| {
            bad(
                format!("--clip {c}: expected AXIS=VALUE with AXIS x, y or z (e.g. x=0.5)"),
                None,
            )
        })?),
    };
    Ok(RenderOptions {
        width,
        height,
        view,
        up,
        colour,
        edges: a.edges,
        clip,
        shading: !a.no_shading && a.shading != "none",
        smooth: a.shading == "smooth",
        camera,
        frame: None,
        title: Some(a.title.clone().unwrap_or(title)),
        legend: !a.no_legend,
        kv: a.kv,
        attribute,
    })
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Png,
    Svg,
}

fn picture_kind(out: &Path) -> Result<Kind, CliError> {
    let ext = out
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("png") => Ok(Kind::Png),
        Some("svg") => Ok(Kind::Svg),
        _ => Err(bad(
            format!(
                "{}: the picture must be a .png or a .svg file",
                out.display()
            ),
            None,
        )),
    }
}

fn file_title(p: &Path) -> String {
    p.file_name().map_or_else(
        || p.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// Renders `k` to `out` with `o` (beside `other` if given), reusing `given`; prints what was
/// drawn.
pub fn render_to(
    ctx: &Ctx,
    k: &IndexedComplex,
    other: Option<(&IndexedComplex, String)>,
    out: &Path,
    o: &RenderOptions,
    given: Given,
) -> Result<(), CliError> {
    let kind = picture_kind(out)?;
    let rerr = |e: render::RenderError| bad(format!("render: {e}"), None);
    let t0 = Instant::now();
    let c0 = starplex::measure::process_cpu_seconds();
    let summary = match kind {
        Kind::Svg => {
            if other.is_some() {
                return Err(bad("--compare writes PNG only".into(), None));
            }
            let (doc, summary) = render::render_svg_with(k, o, given).map_err(rerr)?;
            output::write_with(out, |w| Ok(w.write_all(doc.as_bytes())?))?;
            summary
        }
        Kind::Png => {
            let pic = match other {
                None => render::render_with(k, o, given).map_err(rerr)?,
                Some((k2, title2)) => {
                    // both halves framed by the box around both: same view, same scale
                    let half = RenderOptions {
                        width: o.width.div_ceil(2).max(1),
                        frame: o.frame.or_else(|| render::frame_around(&[k, k2])),
                        ..o.clone()
                    };
                    let a = render::render(k, &half).map_err(rerr)?;
                    let b = render::render(
                        k2,
                        &RenderOptions {
                            title: Some(title2),
                            ..half
                        },
                    )
                    .map_err(rerr)?;
                    a.beside(&b)
                }
            };
            output::write_with(out, |w| render::write_png(&pic, w))?;
            pic.summary
        }
    };
    for n in &summary.notes {
        eprintln!("note: {n}");
    }
    if !ctx.quiet {
        let cpu = c0
            .and_then(|c| Some(starplex::measure::process_cpu_seconds()? - c))
            .map_or(String::new(), |c| format!(", cpu {c:.2} s"));
        eprintln!(
            "wrote {} ({} faces, {} lines, {} dots; render and write {:.2} s{cpu})",
            common::shown(out),
            summary.n_faces,
            summary.n_lines,
            summary.n_points,
            t0.elapsed().as_secs_f64()
        );
        for (_, line) in summary.legend.iter().skip(1) {
            eprintln!("  {line}");
        }
    }
    Ok(())
}

pub fn run(ctx: &Ctx, a: &RenderArgs) -> Result<(), CliError> {
    let o = options(a, file_title(&a.input.file))?;
    picture_kind(&a.output)?;
    let r = common::load(ctx, &a.input)?;
    let other = match &a.compare {
        None => None,
        Some(p) => {
            let args = InputArgs {
                file: p.clone(),
                ..a.input.clone()
            };
            let r2 = common::load(ctx, &args)?;
            Some((r2.complex, file_title(p)))
        }
    };
    render_to(
        ctx,
        &r.complex,
        other.as_ref().map(|(k, t)| (k, t.clone())),
        &a.output,
        &o,
        Given::default(),
    )
}

/// For the `--render OUT` shortcuts of other commands: the picture with default options and the
/// given colouring, reusing the command's own results (`given`: its validation or its tree).
pub fn shortcut(
    ctx: &Ctx,
    k: Option<&IndexedComplex>,
    file: &Path,
    out: &Path,
    colour: ColorMode,
    kv: Option<u32>,
    given: Given,
) -> Result<(), CliError> {
    let k = k.ok_or_else(|| {
        CliError::Input(
            "--render needs the mesh file, not a saved tree".into(),
            None,
        )
    })?;
    let o = RenderOptions {
        width: 1600,
        height: 1200,
        colour,
        kv,
        title: Some(file_title(file)),
        ..Default::default()
    };
    render_to(ctx, k, None, out, &o, given)
}
