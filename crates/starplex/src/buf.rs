//! [`Buf`]: a read-only array that is owned, borrowed from a memory map, or borrowed from
//! another owner's immutable memory ([`SharedBytes`]: a read-only NumPy array, for instance).
//!
//! The binary format is loaded without copying: its arrays stay in the mapped file and are read
//! through `Buf`. Mutation first makes an owned copy ([`Buf::to_mut`]).
//!
//! ```
//! use starplex::buf::Buf;
//! let mut b: Buf<u32> = Buf::from(vec![1, 2, 3]);
//! assert_eq!(&b[..], &[1, 2, 3]);
//! b.to_mut().push(4);
//! assert_eq!(b.len(), 4);
//! ```
use std::ops::Deref;
use std::sync::Arc;

/// Memory that some other owner keeps alive and never changes while it is shared: the bytes
/// behind a [`Buf::Shared`]. The Python bindings implement it for read-only NumPy arrays, so a
/// complex can be built over them without a copy.
///
/// ```
/// use std::sync::Arc;
/// use starplex::buf::{Buf, SharedBytes};
/// struct Frozen(Vec<u32>); // stands for memory owned elsewhere
/// impl SharedBytes for Frozen {
///     fn bytes(&self) -> &[u8] {
///         bytemuck::cast_slice(&self.0)
///     }
/// }
/// let b: Buf<u32> = Buf::shared(Arc::new(Frozen(vec![1, 2]))).unwrap();
/// assert_eq!(&b[..], &[1, 2]);
/// assert!(b.is_shared() && !b.is_mapped());
/// ```
pub trait SharedBytes: Send + Sync + 'static {
    /// The bytes; the same slice (address and length) on every call, never written to while
    /// the value lives.
    fn bytes(&self) -> &[u8];
}

/// Owned or borrowed (memory-mapped or shared) array of plain-old-data values.
///
/// ```
/// use starplex::buf::Buf;
/// let b: Buf<f64> = Buf::Owned(vec![0.5, 1.5]);
/// assert_eq!(b.iter().sum::<f64>(), 2.0); // reads like a slice
/// assert!(!b.is_mapped());
/// assert_eq!(b, Buf::from(vec![0.5, 1.5]));
/// ```
#[derive(Clone)]
pub enum Buf<T: bytemuck::Pod> {
    /// An owned vector.
    Owned(Vec<T>),
    /// `len` values starting `offset` bytes into a shared memory map (offset aligned for `T`).
    Mapped {
        /// The map, kept alive while any buffer refers to it.
        map: Arc<memmap2::Mmap>,
        /// Byte offset of the first value.
        offset: usize,
        /// Number of values.
        len: usize,
    },
    /// All of another owner's immutable bytes (aligned for `T`, a whole number of values);
    /// made by [`Buf::shared`], which checks both.
    Shared(Arc<dyn SharedBytes>),
}

impl<T: bytemuck::Pod> Buf<T> {
    /// The values, copied into an owned vector first when they are mapped.
    ///
    /// ```
    /// use starplex::buf::Buf;
    /// let mut b = Buf::from(vec![3u32, 1, 2]);
    /// b.to_mut().sort();
    /// assert_eq!(&b[..], &[1, 2, 3]);
    /// ```
    pub fn to_mut(&mut self) -> &mut Vec<T> {
        if !matches!(self, Buf::Owned(_)) {
            *self = Buf::Owned(self.deref().to_vec());
        }
        match self {
            Buf::Owned(v) => v,
            Buf::Mapped { .. } | Buf::Shared(_) => unreachable!("converted to owned above"),
        }
    }

    /// A buffer over all of `owner`'s bytes, without a copy; `None` when they are not aligned
    /// for `T` or not a whole number of values.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use starplex::buf::{Buf, SharedBytes};
    /// struct Three([u8; 3]);
    /// impl SharedBytes for Three {
    ///     fn bytes(&self) -> &[u8] { &self.0 }
    /// }
    /// assert!(Buf::<u8>::shared(Arc::new(Three([1, 2, 3]))).is_some());
    /// assert!(Buf::<u16>::shared(Arc::new(Three([1, 2, 3]))).is_none()); // 1.5 values
    /// ```
    pub fn shared(owner: Arc<dyn SharedBytes>) -> Option<Buf<T>> {
        let b = owner.bytes();
        let size = std::mem::size_of::<T>();
        let aligned = (b.as_ptr() as usize).is_multiple_of(std::mem::align_of::<T>());
        (aligned && b.len().is_multiple_of(size.max(1))).then_some(Buf::Shared(owner))
    }

    /// True when the values are borrowed from another owner ([`Buf::shared`]).
    ///
    /// ```
    /// use starplex::buf::Buf;
    /// assert!(!Buf::from(vec![1u32]).is_shared());
    /// ```
    pub fn is_shared(&self) -> bool {
        matches!(self, Buf::Shared(_))
    }

    /// True when the values live in a memory map.
    ///
    /// ```
    /// use starplex::buf::Buf;
    /// // Buffers built in memory are owned; the binary reader returns mapped ones.
    /// assert!(!Buf::from(vec![1u32]).is_mapped());
    /// ```
    pub fn is_mapped(&self) -> bool {
        matches!(self, Buf::Mapped { .. })
    }

    /// Takes the values out as a vector (copies when mapped).
    ///
    /// ```
    /// use starplex::buf::Buf;
    /// let b = Buf::from(vec![7u32, 8]);
    /// assert_eq!(b.into_vec(), vec![7, 8]);
    /// ```
    pub fn into_vec(self) -> Vec<T> {
        match self {
            Buf::Owned(v) => v,
            Buf::Mapped { .. } | Buf::Shared(_) => self.deref().to_vec(),
        }
    }
}

impl<T: bytemuck::Pod> Deref for Buf<T> {
    type Target = [T];
    #[inline]
    fn deref(&self) -> &[T] {
        match self {
            Buf::Owned(v) => v,
            Buf::Mapped { map, offset, len } => {
                let bytes = &map[*offset..*offset + *len * std::mem::size_of::<T>()];
                bytemuck::cast_slice(bytes)
            }
            // alignment and length checked by `Buf::shared`, and the owner's bytes never change
            Buf::Shared(owner) => bytemuck::cast_slice(owner.bytes()),
        }
    }
}

impl<T: bytemuck::Pod> From<Vec<T>> for Buf<T> {
    fn from(v: Vec<T>) -> Self {
        Buf::Owned(v)
    }
}

impl<T: bytemuck::Pod> Default for Buf<T> {
    fn default() -> Self {
        Buf::Owned(Vec::new())
    }
}

impl<T: bytemuck::Pod + std::fmt::Debug> std::fmt::Debug for Buf<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let s: &[T] = self;
        f.debug_struct("Buf")
            .field("mapped", &self.is_mapped())
            .field("shared", &self.is_shared())
            .field("len", &s.len())
            .finish()
    }
}

impl<T: bytemuck::Pod + PartialEq> PartialEq for Buf<T> {
    fn eq(&self, other: &Self) -> bool {
        self.deref() == other.deref()
    }
}

/// Arrays of at least this many bytes are offered to the kernel for transparent huge pages.
const HUGE_MIN_BYTES: usize = 4 << 20;

/// A vector of `n` zeros for a large scratch or result array of a build.
///
/// On Linux, when the array spans at least 4 MiB, its not yet touched pages are marked for
/// transparent huge pages (`madvise(MADV_HUGEPAGE)`, which takes effect where the system's
/// setting is `madvise` or `always`): 2 MiB pages mean 512 times fewer page faults and far
/// fewer TLB misses for the random writes of a counting sort. Elsewhere, or if the kernel
/// refuses, it is an ordinary zeroed vector.
///
/// ```
/// use starplex::buf::large_zeroed;
/// let v: Vec<u64> = large_zeroed(1 << 20); // 8 MiB
/// assert_eq!(v.len(), 1 << 20);
/// assert!(v.iter().all(|&x| x == 0));
/// ```
pub fn large_zeroed<T: bytemuck::Pod>(n: usize) -> Vec<T> {
    // a zeroed allocation (calloc): fresh pages are not touched, so the advice still applies
    // to them and the kernel's zeroing is the only one
    let mut v = vec![T::zeroed(); n];
    advise_huge(&mut v);
    v
}

/// A vector of `n` values made by `f`, with the huge-page advice of [`large_zeroed`] given
/// before the values are written (for types that cannot be calloc'd, such as atomics).
///
/// ```
/// use std::sync::atomic::{AtomicU32, Ordering};
/// use starplex::buf::large_with;
/// let v = large_with(3, || AtomicU32::new(7));
/// v[1].store(9, Ordering::Relaxed);
/// assert_eq!(v[1].load(Ordering::Relaxed), 9);
/// ```
pub fn large_with<T>(n: usize, f: impl FnMut() -> T) -> Vec<T> {
    let mut v = Vec::with_capacity(n);
    advise_huge(&mut v);
    v.extend(std::iter::repeat_with(f).take(n));
    v
}

/// Marks the 2 MiB-aligned part of `v`'s allocation for transparent huge pages.
#[cfg(target_os = "linux")]
fn advise_huge<T>(v: &mut Vec<T>) {
    const HUGE: usize = 2 << 20;
    let bytes = v.capacity().saturating_mul(std::mem::size_of::<T>());
    if bytes < HUGE_MIN_BYTES {
        return;
    }
    let p = v.as_mut_ptr() as usize;
    let start = p.div_ceil(HUGE) * HUGE;
    let end = (p + bytes) / HUGE * HUGE;
    if end > start {
        // SAFETY: [start, end) lies inside the allocation `v` owns, borrowed mutably here;
        // MADV_HUGEPAGE changes how the kernel backs those pages, never their contents or
        // validity, and a failure (an old kernel, THP disabled) leaves the memory as it was.
        unsafe {
            libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE);
        }
    }
}

#[cfg(not(target_os = "linux"))]
fn advise_huge<T>(_v: &mut Vec<T>) {}

/// Asks the processor to bring `s[i]` into the cache (no effect elsewhere than x86-64, nor
/// when `i` is out of range).
#[inline(always)]
pub(crate) fn prefetch(s: &[u32], i: usize) {
    #[cfg(target_arch = "x86_64")]
    if i < s.len() {
        // SAFETY: a prefetch never faults, and the address is inside `s`.
        unsafe {
            use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
            _mm_prefetch::<_MM_HINT_T0>(s.as_ptr().add(i) as *const i8);
        }
    }
}

/// `s` seen as atomics, for writes from several threads to places each owned by one writer
/// (relaxed stores compile to plain stores; `AtomicU32` has the layout of `u32`).
pub(crate) fn atomic_view(s: &mut [u32]) -> &[std::sync::atomic::AtomicU32] {
    // SAFETY: `AtomicU32` has the same size, alignment and bit validity as `u32`, and the
    // exclusive borrow of `s` guarantees no other access for the returned lifetime.
    unsafe { &*(s as *mut [u32] as *const [std::sync::atomic::AtomicU32]) }
}

/// The inverse of the permutation `p` (`inv[p[i]] = i`), written by all threads: the random
/// writes of a large inversion are the serial tail of a parallel phase otherwise.
///
/// ```
/// use starplex::buf::invert;
/// assert_eq!(invert(&[2, 0, 1]), vec![1, 2, 0]);
/// ```
///
/// # Panics
/// When an entry of `p` is not below `p.len()` (`p` must be a permutation; when an id repeats,
/// which position it maps to is unspecified).
pub fn invert(p: &[u32]) -> Vec<u32> {
    let mut inv = vec![0u32; p.len()];
    invert_into(p, &mut inv);
    inv
}

/// [`invert`] into `inv` (of `p.len()` entries; every entry is overwritten when `p` is a
/// permutation).
///
/// ```
/// let mut inv = vec![7u32; 3];
/// starplex::buf::invert_into(&[1, 2, 0], &mut inv);
/// assert_eq!(inv, [2, 0, 1]);
/// ```
///
/// # Panics
/// As [`invert`], and when `inv` is shorter than `p`.
pub fn invert_into(p: &[u32], inv: &mut [u32]) {
    use rayon::prelude::*;
    use std::sync::atomic::Ordering::Relaxed;
    let out = atomic_view(inv);
    p.par_chunks(1 << 16).enumerate().for_each(|(k, ch)| {
        let base = (k << 16) as u32;
        for (i, &x) in (base..).zip(ch) {
            out[x as usize].store(i, Relaxed);
        }
    });
}
