//! What the process costs: CPU time (of the process or of the calling thread), resident memory
//! and its peak, memory still available. One home for the timers the CLI's `bench`, `stellar
//! --bench`, `render` and the MPI binary report. Linux reads `/proc`; elsewhere every function
//! answers `None` (or `false`), never a made-up number.
//!
//! CPU time is less sensitive than wall time to other processes on a shared machine, so the
//! benchmarks report both.
//!
//! ```
//! use starplex::measure;
//! let c0 = measure::process_cpu_seconds();
//! let x: u64 = (0..1_000_000u64).map(|i| i * i % 7).sum();
//! if let (Some(a), Some(b)) = (c0, measure::process_cpu_seconds()) {
//!     assert!(b >= a);
//! }
//! assert!(x > 0);
//! ```

/// CPU seconds used by this process so far (user + system, all threads), from
/// `/proc/self/stat` (clock ticks of 1/100 s); `None` where unsupported.
///
/// ```
/// if let Some(s) = starplex::measure::process_cpu_seconds() { assert!(s >= 0.0); }
/// ```
pub fn process_cpu_seconds() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/self/stat").ok()?;
    // the command name (field 2) may hold spaces: count fields after its closing parenthesis
    let rest = s.get(s.rfind(')')? + 2..)?;
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ut: f64 = f.get(11)?.parse().ok()?;
    let st: f64 = f.get(12)?.parse().ok()?;
    Some((ut + st) / 100.0)
}

/// CPU seconds of the calling thread (`/proc/thread-self/schedstat`, nanoseconds), for timing
/// a single-threaded section on a loaded machine; `None` where unsupported.
///
/// ```
/// if let Some(s) = starplex::measure::thread_cpu_seconds() { assert!(s >= 0.0); }
/// ```
pub fn thread_cpu_seconds() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: u64 = s.split_whitespace().next()?.parse().ok()?;
    Some(ns as f64 * 1e-9)
}

/// Resident memory of this process, in bytes.
///
/// ```
/// if let Some(m) = starplex::measure::memory() { assert!(m.peak >= m.resident); }
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Memory {
    /// Resident now (`VmRSS`).
    pub resident: u64,
    /// Peak resident since start or since [`reset_peak`] (`VmHWM`).
    pub peak: u64,
}

/// This process's resident memory now and at its peak; `None` where unsupported.
///
/// ```
/// let m = starplex::measure::memory();
/// # let _ = m;
/// ```
pub fn memory() -> Option<Memory> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let get = |key: &str| -> Option<u64> {
        let l = s.lines().find(|l| l.starts_with(key))?;
        Some(l.split_whitespace().nth(1)?.parse::<u64>().ok()? * 1024)
    };
    Some(Memory {
        resident: get("VmRSS:")?,
        peak: get("VmHWM:")?,
    })
}

/// Resets the peak counter of [`memory`] to the current resident size (Linux `clear_refs`
/// 5); false where unsupported.
///
/// ```
/// let _supported: bool = starplex::measure::reset_peak();
/// ```
pub fn reset_peak() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

/// Memory the system can still give without swapping (`MemAvailable` of `/proc/meminfo`), in
/// bytes; `None` where unsupported.
///
/// ```
/// if let Some(b) = starplex::measure::available_memory() { assert!(b > 0); }
/// ```
pub fn available_memory() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/meminfo").ok()?;
    let l = s.lines().find(|l| l.starts_with("MemAvailable:"))?;
    Some(l.split_whitespace().nth(1)?.parse::<u64>().ok()? * 1024)
}
