//! What the polygon-face readers (PLY, OBJ) share: a face made into cells as
//! [`PolygonMode`] says, with a count of the fan-triangulated polygons, and the notes of the
//! complex build.

use super::PolygonMode;
use crate::cell::CellKind;
use crate::complex::{BuildReport, ComplexBuilder, ComplexError};

/// Why a face could not become cells.
pub(crate) enum FaceError {
    /// The builder refused a cell.
    Complex(ComplexError),
    /// A polygon of fewer than 3 vertices (this many).
    TooFew(usize),
    /// A face of this many vertices is no simplex (1 to 65 vertices).
    NotSimplex(usize),
}

/// Faces made into cells, and how many polygons were fan-triangulated on the way.
#[derive(Default)]
pub(crate) struct Faces {
    /// Polygons of more than 4 vertices, fan-triangulated.
    pub(crate) fanned: u64,
    /// The triangles they became.
    pub(crate) fan_triangles: u64,
}

impl Faces {
    /// Pushes the face `verts` into `b` as `mode` says: a triangle, a quad or a fan of
    /// triangles (polygons), or one (k-1)-simplex (simplices). Returns the number of cells
    /// pushed.
    pub(crate) fn push(
        &mut self,
        b: &mut ComplexBuilder,
        mode: PolygonMode,
        verts: &[u32],
    ) -> Result<usize, FaceError> {
        let k = verts.len();
        let mut push = |kind: CellKind, v: &[u32]| {
            b.push_cell(kind, v).map(|_| ()).map_err(FaceError::Complex)
        };
        match mode {
            PolygonMode::Polygons => match k {
                3 => push(CellKind::Simplex(2), verts).map(|()| 1),
                4 => push(CellKind::Quad, verts).map(|()| 1),
                k if k > 4 => {
                    for j in 1..k - 1 {
                        push(CellKind::Simplex(2), &[verts[0], verts[j], verts[j + 1]])?;
                    }
                    self.fanned += 1;
                    self.fan_triangles += k as u64 - 2;
                    Ok(k - 2)
                }
                _ => Err(FaceError::TooFew(k)),
            },
            PolygonMode::Simplices => {
                let kind = k
                    .checked_sub(1)
                    .and_then(CellKind::simplex)
                    .ok_or(FaceError::NotSimplex(k))?;
                push(kind, verts).map(|()| 1)
            }
        }
    }

    /// The note on fan-triangulated polygons, if any.
    pub(crate) fn note(&self, notes: &mut Vec<String>) {
        if self.fanned > 0 {
            notes.push(format!(
                "fan-triangulated {} polygons of more than 4 vertices into {} triangles",
                self.fanned, self.fan_triangles
            ));
        }
    }
}

/// The notes of a complex build: degenerate cells, duplicate cells and cells that were faces of
/// others, dropped.
pub(crate) fn push_build_notes(notes: &mut Vec<String>, report: &BuildReport) {
    push_degenerate_note(notes, report);
    if report.dropped_duplicates > 0 {
        notes.push(format!(
            "dropped {} duplicate cells",
            report.dropped_duplicates
        ));
    }
    if report.dropped_face_cells > 0 {
        notes.push(format!(
            "dropped {} cells that are faces of other cells",
            report.dropped_face_cells
        ));
    }
}

/// The note on cells dropped for a repeated vertex (`--drop-degenerate`), if any.
pub(crate) fn push_degenerate_note(notes: &mut Vec<String>, report: &BuildReport) {
    if report.dropped_degenerate > 0 {
        notes.push(format!(
            "dropped {} degenerate cells (a vertex repeated in the cell)",
            report.dropped_degenerate
        ));
    }
}
