//! The few collective operations `starplex-mpi` uses, over rsmpi: the all-to-all exchange of
//! per-rank vectors, reductions, a gather to rank 0, and the collective error check run before
//! every phase (no rank ever waits for a rank that has failed).
use std::sync::atomic::{AtomicU64, Ordering};

use mpi::collective::SystemOperation;
use mpi::datatype::{Partition, PartitionMut};
use mpi::traits::*;

/// The communicator every phase runs on.
pub type World = mpi::topology::SimpleCommunicator;

/// Bytes this rank sent to other ranks in [`exchange`] and [`gather`] (for the benchmarks).
static BYTES_SENT: AtomicU64 = AtomicU64::new(0);

/// Bytes sent to other ranks so far.
pub fn bytes_sent() -> u64 {
    BYTES_SENT.load(Ordering::Relaxed)
}

/// An error every rank agrees on: rank 0 prints it, every rank exits with status 2.
#[derive(Debug)]
pub struct Failure(pub String);

fn rank_of(w: &World) -> usize {
    w.rank() as usize
}

/// The collective error check: every rank contributes whether `r` is an error; when one is, every
/// rank returns the error of the lowest failing rank.
pub fn agree<T>(w: &World, r: Result<T, String>) -> Result<T, Failure> {
    let size = w.size();
    let mine: i32 = if r.is_err() { w.rank() } else { size };
    let mut first = size;
    w.all_reduce_into(&mine, &mut first, SystemOperation::min());
    if first == size {
        return Ok(r.unwrap_or_else(|_| unreachable!("no rank failed")));
    }
    let root = w.process_at_rank(first);
    let mut msg = match &r {
        Err(e) if w.rank() == first => e.clone().into_bytes(),
        _ => Vec::new(),
    };
    let mut len = msg.len() as u64;
    root.broadcast_into(&mut len);
    msg.resize(len as usize, 0);
    root.broadcast_into(&mut msg[..]);
    let text = String::from_utf8_lossy(&msg).into_owned();
    Err(Failure(if size > 1 {
        format!("{text} (rank {first})")
    } else {
        text
    }))
}

fn counts_of(lens: impl Iterator<Item = usize>) -> Result<Vec<i32>, String> {
    lens.map(|n| {
        i32::try_from(n).map_err(|_| {
            format!("{n} values to send to one rank exceed MPI's 32-bit counts: use more ranks")
        })
    })
    .collect()
}

fn displs(counts: &[i32]) -> Vec<i32> {
    let mut d = Vec::with_capacity(counts.len());
    let mut at = 0i32;
    for &c in counts {
        d.push(at);
        at = at.saturating_add(c);
    }
    d
}

/// What every rank sent here in an [`exchange`], by source rank, in one array (no copy per
/// source).
pub struct Received<T> {
    flat: Vec<T>,
    starts: Vec<usize>,
}

impl<T> Received<T> {
    /// What rank `r` sent.
    pub fn part(&self, r: usize) -> &[T] {
        &self.flat[self.starts[r]..self.starts[r + 1]]
    }
    /// The parts, by source rank.
    pub fn parts(&self) -> impl Iterator<Item = &[T]> {
        (0..self.starts.len() - 1).map(|r| self.part(r))
    }
    /// Everything received, in source-rank order.
    pub fn into_flat(self) -> Vec<T> {
        self.flat
    }
}

/// All-to-all: `out[r]` goes to rank `r` (each part freed as it is packed); returns what
/// every rank sent here, by source rank.
pub fn exchange<T>(w: &World, out: Vec<Vec<T>>) -> Result<Received<T>, Failure>
where
    T: Equivalence + Default + Clone,
{
    let counts: Vec<usize> = out.iter().map(Vec::len).collect();
    let mut flat: Vec<T> = Vec::with_capacity(counts.iter().sum());
    for part in out {
        flat.extend_from_slice(&part);
    }
    exchange_packed(w, flat, &counts)
}

/// All-to-all of a send buffer already packed by destination: the first `counts[0]` values go
/// to rank 0, the next `counts[1]` to rank 1, and so on.
pub fn exchange_packed<T>(w: &World, flat: Vec<T>, counts: &[usize]) -> Result<Received<T>, Failure>
where
    T: Equivalence + Default + Clone,
{
    let p = w.size() as usize;
    let send_counts = agree(w, counts_of(counts.iter().copied()))?;
    let mut recv_counts = vec![0i32; p];
    w.all_to_all_into(&send_counts[..], &mut recv_counts[..]);
    let total: i64 = recv_counts.iter().map(|&c| c as i64).sum();
    agree(
        w,
        if total > i32::MAX as i64 {
            Err(format!(
                "{total} values to receive exceed MPI's 32-bit displacements: use more ranks"
            ))
        } else {
            Ok(())
        },
    )?;
    let me = rank_of(w);
    let sent: usize = counts
        .iter()
        .enumerate()
        .filter(|&(r, _)| r != me)
        .map(|(_, &c)| c)
        .sum();
    BYTES_SENT.fetch_add((sent * std::mem::size_of::<T>()) as u64, Ordering::Relaxed);
    let (sd, rd) = (displs(&send_counts), displs(&recv_counts));
    let mut recv = vec![T::default(); total as usize];
    {
        let s = Partition::new(&flat[..], &send_counts[..], &sd[..]);
        let mut r = PartitionMut::new(&mut recv[..], &recv_counts[..], &rd[..]);
        w.all_to_all_varcount_into(&s, &mut r);
    }
    drop(flat);
    let mut starts: Vec<usize> = rd.iter().map(|&d| d as usize).collect();
    starts.push(total as usize);
    Ok(Received { flat: recv, starts })
}

/// [`agree`] on a condition: every rank fails with `what` when it is false on any rank.
pub fn agree_that(w: &World, ok: bool, what: &str) -> Result<(), Failure> {
    agree(w, if ok { Ok(()) } else { Err(what.to_string()) })
}

/// Gathers every rank's `v` on rank 0 (in rank order); `None` on the other ranks.
pub fn gather<T>(w: &World, v: &[T]) -> Result<Option<Vec<T>>, Failure>
where
    T: Equivalence + Default + Clone,
{
    let root = w.process_at_rank(0);
    let n = agree(w, counts_of(std::iter::once(v.len())))?[0];
    if w.rank() != 0 {
        BYTES_SENT.fetch_add(std::mem::size_of_val(v) as u64, Ordering::Relaxed);
        root.gather_into(&n);
        root.gather_varcount_into(v);
        return Ok(None);
    }
    let mut counts = vec![0i32; w.size() as usize];
    root.gather_into_root(&n, &mut counts[..]);
    let total: i64 = counts.iter().map(|&c| c as i64).sum();
    let mut all = vec![T::default(); total as usize];
    let d = displs(&counts);
    {
        let mut r = PartitionMut::new(&mut all[..], &counts[..], &d[..]);
        root.gather_varcount_into_root(v, &mut r);
    }
    Ok(Some(all))
}

/// Sum over ranks.
pub fn sum(w: &World, x: u64) -> u64 {
    let mut y = 0u64;
    w.all_reduce_into(&x, &mut y, SystemOperation::sum());
    y
}

/// Minimum over ranks.
pub fn min(w: &World, x: u64) -> u64 {
    let mut y = 0u64;
    w.all_reduce_into(&x, &mut y, SystemOperation::min());
    y
}

/// Maximum over ranks.
pub fn max(w: &World, x: u64) -> u64 {
    let mut y = 0u64;
    w.all_reduce_into(&x, &mut y, SystemOperation::max());
    y
}

/// Sum over ranks of a float.
pub fn sum_f64(w: &World, x: f64) -> f64 {
    let mut y = 0.0f64;
    w.all_reduce_into(&x, &mut y, SystemOperation::sum());
    y
}

/// Element-wise sums over ranks (every rank passes the same length).
pub fn sums(w: &World, x: &[u64]) -> Vec<u64> {
    let mut y = vec![0u64; x.len()];
    w.all_reduce_into(x, &mut y[..], SystemOperation::sum());
    y
}

/// Element-wise minima and maxima over ranks.
pub fn min_max(w: &World, lo: &[f64], hi: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let (mut a, mut b) = (vec![0.0; lo.len()], vec![0.0; hi.len()]);
    w.all_reduce_into(lo, &mut a[..], SystemOperation::min());
    w.all_reduce_into(hi, &mut b[..], SystemOperation::max());
    (a, b)
}

/// Every rank's `v`, on every rank, concatenated in rank order.
pub fn all_gather(w: &World, v: &[u64]) -> Vec<u64> {
    let n = v.len() as i32;
    let mut counts = vec![0i32; w.size() as usize];
    w.all_gather_into(&n, &mut counts[..]);
    let total: usize = counts.iter().map(|&c| c as usize).sum();
    let mut all = vec![0u64; total];
    let d = displs(&counts);
    {
        let mut r = PartitionMut::new(&mut all[..], &counts[..], &d[..]);
        w.all_gather_varcount_into(v, &mut r);
    }
    all
}
