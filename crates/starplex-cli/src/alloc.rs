//! The allocator setting of the command-line front ends.

/// Fixes glibc's mmap threshold at its default of 128 KiB, so that every large array is mapped
/// on its own and goes back to the system when it is freed.
///
/// Without it glibc raises the threshold each time a mapped block is freed (up to 32 MiB), and
/// the next arrays of that size come from the heap, where freed space stays resident: peak RSS
/// measured on this project's 2-core machine (`/usr/bin/time`, 5 runs each, same times within
/// noise): `homology` of tet_armadillo_m 31.3 → 28.7 MB, of tri_armadillo_x16 37.0 → 34.5 MB;
/// `simplify` of tet_armadillo_m 128 → 84 MB, of tri_armadillo_x16 194 → 155 MB; `query --all`
/// 98 → 86 MB. Elsewhere (other C libraries, other systems) this does nothing.
///
/// ```
/// starplex_cli::alloc::tune();
/// let v = vec![0u8; 1 << 20]; // mapped on its own, unmapped when dropped
/// assert_eq!(v.len(), 1 << 20);
/// ```
pub fn tune() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only changes a malloc parameter; it is called before the program's
    // threads start, and M_MMAP_THRESHOLD with 128 KiB is a valid setting (glibc's default).
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 128 * 1024);
    }
}
