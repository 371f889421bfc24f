//! Lane code compiled for the widest SIMD instruction set the CPU has,
//! chosen at run time: the loops inlined into [`with`] use its registers
//! (AVX-512: 8 f64 lanes, AVX2: 4, the SSE2 every x86-64 has: 2). Fused
//! multiply-add stays off: every result keeps its bits whatever the set.

/// [`Isa::Avx2`]'s features, written in one place: `avx2_set!(check)`
/// says whether the CPU has them all, `avx2_set! { fn … }` compiles the
/// function for them (an attribute takes only a literal, so the list is
/// written twice, side by side).
macro_rules! avx2_set {
    (check) => {{
        use std::arch::is_x86_feature_detected as has;
        has!("avx2") && has!("popcnt") && has!("bmi1") && has!("bmi2") && has!("lzcnt")
    }};
    ($(#[$meta:meta])* $vis:vis fn $($rest:tt)*) => {
        $(#[$meta])*
        #[target_feature(enable = "avx2,popcnt,bmi1,bmi2,lzcnt")]
        $vis fn $($rest)*
    };
}
pub(crate) use avx2_set;

/// An instruction set the reference's lane code is compiled for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Isa {
    /// What the target has without run-time detection (SSE2 on x86-64).
    Baseline,
    /// AVX2, with the bit instructions every AVX2 CPU has (POPCNT, BMI1,
    /// BMI2, LZCNT): a walk's `count_ones` was a dozen instructions
    /// without POPCNT (engine's process 33 M and 1 M triangles' 83 M
    /// instructions more, the renders 2–5 % slower).
    Avx2,
    /// AVX-512 F and DQ.
    Avx512,
}

impl Isa {
    /// Those this CPU runs, narrowest first (the tests run each).
    #[cfg(test)]
    pub fn available() -> Vec<Isa> {
        [Isa::Baseline, Isa::Avx2, Isa::Avx512]
            .into_iter()
            .filter(|isa| isa.runs())
            .collect()
    }

    /// The widest this CPU runs.
    #[inline]
    pub fn widest() -> Isa {
        if Isa::Avx512.runs() {
            Isa::Avx512
        } else if Isa::Avx2.runs() {
            Isa::Avx2
        } else {
            Isa::Baseline
        }
    }

    /// Whether this CPU runs it.
    #[inline]
    pub fn runs(self) -> bool {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::is_x86_feature_detected as has;
            match self {
                Isa::Baseline => true,
                Isa::Avx2 => avx2_set!(check),
                Isa::Avx512 => has!("avx512f") && has!("avx512dq"),
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            self == Isa::Baseline
        }
    }
}

/// Runs `f` compiled for `isa` where the CPU has it (the code inlined in
/// `f` then uses its registers), as it is otherwise.
#[inline(always)]
pub fn with<R>(isa: Isa, f: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    {
        #[target_feature(enable = "avx512f,avx512dq")]
        fn avx512<R>(f: impl FnOnce() -> R) -> R {
            f()
        }
        avx2_set! {
            fn avx2<R>(f: impl FnOnce() -> R) -> R {
                f()
            }
        }
        if isa == Isa::Avx512 && isa.runs() {
            // SAFETY: the CPU has AVX-512 F and DQ.
            return unsafe { avx512(f) };
        }
        if isa == Isa::Avx2 && isa.runs() {
            // SAFETY: the CPU has AVX2.
            return unsafe { avx2(f) };
        }
    }
    f()
}

/// Asks for the cache line at `at` ahead of its use: a hint, which changes
/// no result (no address faults, nothing is read).
#[inline(always)]
pub fn prefetch<T>(at: *const T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch reads nothing and faults on no address.
    unsafe {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        _mm_prefetch::<_MM_HINT_T0>(at.cast());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = at;
}
