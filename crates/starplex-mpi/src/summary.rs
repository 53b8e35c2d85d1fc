//! The topology of a `.spb` computed over the ranks: what `starplex simplify` reports before
//! and after ([`starplex::algo::simplify::summary`]), each part by the distributed verb that
//! computes it: the f-vector from the faces counted by their owners (`info`), the non-manifold
//! vertices and edges and the boundary faces from the validation of the owned stars
//! (`validate`), the Betti numbers over Z/2 by rank-local Morse reduction (`homology`).
//! The parts the single process leaves out when over its budgets are left out here too: the
//! f-vector over 4·10^9 face visits, the Betti numbers when the interface or a rank's faces
//! pass the homology budgets.
use std::path::Path;

use mpi::traits::Communicator;
use starplex::algo::homology::Field;
use starplex::algo::info::face_visits_of;
use starplex::algo::simplify::TopologySummary;
use starplex::algo::validate::validate_parts;
use starplex::topo::naive::VtIndex;

use crate::comm::{self, agree, Failure, World};
use crate::dist::{self, Spb, SplitKind};

/// Face visits over which the f-vector is not counted (the single process's budget).
const F_VECTOR_FACES: u128 = 4_000_000_000;

/// The topology of the complex in `file` (collective; `Some` on rank 0).
pub fn summary(w: &World, file: &Path) -> Result<Option<TopologySummary>, Failure> {
    let f = agree(w, Spb::open(file))?;
    let split = dist::split(w, &f, SplitKind::Plain)?;
    let mut l = dist::distribute(w, &f, &split)?;
    agree(w, f.check_unchanged())?;
    f.release_pages();
    let d = crate::global_dims(&f).into_iter().max();
    let f_vector = match d {
        None => Some(vec![f.h.n_vertices]),
        Some(_) if face_visits_of(f.h.blocks.iter().map(|&(k, n, _)| (k, n))) > F_VECTOR_FACES => {
            None
        }
        Some(d) => {
            let c = crate::owned_face_counts(w, &l, d);
            let mut v = vec![f.h.n_vertices];
            v.extend_from_slice(&c.per_dim[1..]);
            Some(v)
        }
    };
    let euler_characteristic = f_vector.as_ref().map(|f| {
        f.iter()
            .enumerate()
            .map(|(i, &x)| if i % 2 == 0 { x as i64 } else { -(x as i64) })
            .sum()
    });
    let counts = {
        let view = crate::OwnedStars {
            idx: VtIndex::new(&l.k),
            owned: &l.owned,
        };
        let (r, _) = validate_parts(&view, d);
        let o = crate::owned_lists(&l, &r);
        comm::sums(
            w,
            &[
                o.nm_v.len() as u64,
                (o.nm_e.len() / 2) as u64,
                crate::bnd_len(&o.bnd) as u64,
            ],
        )
    };
    // the Betti numbers: not when the interface would pass the budget (as `homology` then
    // contracts instead) nor when the reduction refuses
    let interface = crate::morse::interface_estimate(&l);
    let betti =
        if comm::max(w, u64::try_from(interface).unwrap_or(u64::MAX)) > crate::morse::AUTO_FACES {
            None
        } else {
            let dims = d.map_or(1, |d| d + 1);
            match crate::morse::reduce(
                w,
                file,
                dims,
                &mut l,
                Field::Z2,
                starplex::limits::INFO_FACES,
            ) {
                Ok(r) => r.map(|r| r.combined.0),
                Err(_) => None,
            }
        };
    Ok((w.rank() == 0).then(|| TopologySummary {
        n_vertices: f.h.n_vertices as usize,
        n_cells: f.h.n_cells as usize,
        f_vector,
        euler_characteristic,
        betti,
        non_manifold_vertices: counts[0] as usize,
        non_manifold_edges: counts[1] as usize,
        boundary_faces: counts[2] as usize,
    }))
}
