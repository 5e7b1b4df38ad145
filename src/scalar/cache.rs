//! The per-kernel cache of exact matrices (degree elevation, L2 reduction,
//! products) converted to each kernel: the sealed supertrait of
//! [`Scalar`](super::Scalar), so that the cache stays out of the public API.

use inari::Interval;
use num_rational::BigRational;
use std::any::{Any, TypeId};
use std::cell::RefCell;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};
use std::sync::{Arc, Mutex, OnceLock};

/// Keys of the per-kernel matrix cache (see [`MatrixCache::cached_matrix`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MatrixKey {
    /// Univariate L2 reduction, degree `n` to `k`.
    UniReduce(usize, usize),
    /// Triangular L2 reduction, degree `n` to `k`.
    TriReduce(usize, usize),
    /// Univariate degree elevation, degree `n` to `m`.
    UniElevate(usize, usize),
    /// Triangular degree elevation, degree `n` to `m`.
    TriElevate(usize, usize),
    /// Tensor bidegree `(m, n)` on the unit square to a triangle of degree `m + n`.
    TensorToTri(usize, usize),
    /// Weights of the triangular BB product of degrees `m` and `n`.
    TriProduct(usize, usize),
    /// Weights of the univariate BB product of degrees `m` and `n`.
    UniProduct(usize, usize),
}

/// The process-wide cache of one kernel.
pub type Cache<S> = Mutex<HashMap<MatrixKey, Arc<[S]>>>;

/// The matrix cache of a kernel; implemented for exactly the kernels of
/// [`Scalar`](super::Scalar), which is what seals that trait.
pub trait MatrixCache: Sized + Clone + Send + Sync + 'static {
    /// The process-wide cache of rational matrices converted to this kernel.
    fn matrix_cache() -> &'static Cache<Self>;

    /// `q` in this kernel (tightest interval, exact, or nearest float).
    fn convert(q: &BigRational) -> Self;

    /// A matrix built once per key in exact arithmetic by `build` and cached
    /// converted to this kernel (tightest intervals for [`Interval`]).
    ///
    /// Hot loops call this per operation, so a thread-local copy answers
    /// repeat lookups without a lock; the process-wide cache behind it
    /// ([`MatrixCache::matrix_cache`]) makes sure each matrix is built once.
    fn cached_matrix(key: MatrixKey, build: impl FnOnce() -> Vec<BigRational>) -> Arc<[Self]> {
        if let Some(m) = local_matrix::<Self>(key) {
            return m;
        }
        let cache = Self::matrix_cache();
        // Bind the lookup first: a guard held across the match would deadlock
        // on the insert below.
        let found = lock(cache).get(&key).cloned();
        let shared = match found {
            Some(m) => m,
            None => {
                let converted: Arc<[Self]> = build().iter().map(Self::convert).collect();
                lock(cache).entry(key).or_insert(converted).clone()
            }
        };
        // A private copy per thread keeps the reference count of a hot matrix
        // off a cache line that other threads write.
        let local: Arc<[Self]> = Arc::from(&shared[..]);
        remember_local_matrix(key, local.clone());
        local
    }
}

/// Per-thread front of the matrix caches, keyed by kernel and matrix.
type LocalCache = HashMap<(TypeId, MatrixKey), Box<dyn Any>, BuildHasherDefault<FxHasher>>;

thread_local! {
    static LOCAL_MATRICES: RefCell<LocalCache> =
        const { RefCell::new(HashMap::with_hasher(BuildHasherDefault::new())) };
}

/// This thread's copy of matrix `key` with entries of type `T`, if any.
pub(crate) fn local_matrix<T: 'static>(key: MatrixKey) -> Option<Arc<[T]>> {
    LOCAL_MATRICES
        .try_with(|c| {
            let cache = c.borrow();
            let entry = cache.get(&(TypeId::of::<T>(), key))?;
            entry.downcast_ref::<Arc<[T]>>().cloned()
        })
        .ok()
        .flatten()
}

pub(crate) fn remember_local_matrix<T: 'static>(key: MatrixKey, m: Arc<[T]>) {
    // During thread teardown the local cache is gone; the global one still
    // answers, so there is nothing to do.
    let _ = LOCAL_MATRICES.try_with(|c| {
        if let Ok(mut cache) = c.try_borrow_mut() {
            cache.insert((TypeId::of::<T>(), key), Box::new(m));
        }
    });
}

/// The multiplicative hash of rustc's `FxHasher`: the keys are a few small
/// integers, for which SipHash's flooding resistance buys nothing and costs
/// more than the rest of a lookup.
#[derive(Default)]
struct FxHasher(u64);

impl Hasher for FxHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(word));
        }
    }
    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
    fn write_usize(&mut self, x: usize) {
        self.write_u64(x as u64);
    }
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    // A panic while holding the lock cannot leave a half-written entry (insert is
    // atomic from the map's view), so a poisoned cache is still sound.
    m.lock().unwrap_or_else(|e| e.into_inner())
}

macro_rules! cache_impl {
    ($t:ty) => {
        impl MatrixCache for $t {
            fn matrix_cache() -> &'static Cache<$t> {
                static CACHE: OnceLock<Cache<$t>> = OnceLock::new();
                CACHE.get_or_init(Default::default)
            }
            fn convert(q: &BigRational) -> Self {
                <$t as super::Scalar>::from_rational(q)
            }
        }
    };
}

cache_impl!(f64);
cache_impl!(Interval);
cache_impl!(BigRational);
