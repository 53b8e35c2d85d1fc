//! SIGBUS protection: a `.spb` truncated while a rank reads it through its memory map raises
//! SIGBUS on the first page past the new end. The handler installed here prints a clear error
//! (written from a buffer prepared beforehand: only async-signal-safe calls in the handler) and
//! ends the rank with status 2; `mpirun` then stops the other ranks (no hang) and exits 2.
//! A file rewritten in place without a change of length is caught by the length/modification
//! time check at the end of each phase instead (`Spb::check_unchanged`).
use std::sync::OnceLock;

static MESSAGE: OnceLock<Vec<u8>> = OnceLock::new();

extern "C" fn on_sigbus(_: libc::c_int) {
    if let Some(m) = MESSAGE.get() {
        // SAFETY: write(2) and _exit(2) are async-signal-safe; `m` was initialised before
        // the handler was installed and is never freed.
        unsafe {
            libc::write(2, m.as_ptr().cast(), m.len());
        }
    }
    // SAFETY: as above.
    unsafe { libc::_exit(2) }
}

/// Installs the handler for reads of `path` (after `MPI_Init`, which installs its own).
pub fn guard_sigbus(path: &std::path::Path) {
    let msg = format!(
        "error: {}: the file changed (it was truncated) while this rank read it through its memory map (SIGBUS); run again on a file that is not being written\n",
        path.display()
    );
    if MESSAGE.set(msg.into_bytes()).is_err() {
        return;
    }
    // SAFETY: a zeroed sigaction with a plain handler and an empty mask is valid; the handler
    // only calls async-signal-safe functions.
    unsafe {
        let mut sa: libc::sigaction = std::mem::zeroed();
        sa.sa_sigaction = on_sigbus as *const () as usize;
        libc::sigemptyset(&mut sa.sa_mask);
        libc::sigaction(libc::SIGBUS, &sa, std::ptr::null_mut());
    }
}

/// Test hook: sleeps `STARPLEX_MPI_PAUSE_AFTER_OPEN_MS` milliseconds after the file is mapped
/// (so a test can truncate it under a running read). Unset: nothing.
pub fn test_pause() {
    if let Some(ms) = std::env::var("STARPLEX_MPI_PAUSE_AFTER_OPEN_MS")
        .ok()
        .and_then(|v| v.parse::<u64>().ok())
    {
        std::thread::sleep(std::time::Duration::from_millis(ms));
    }
}
