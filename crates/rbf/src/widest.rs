//! Element-by-element loops compiled for the widest vectors the processor has.
//!
//! The workspace builds for the baseline x86-64 target (two f64 lanes); a loop written
//! with [`widest!`] is also compiled for AVX-512 and for AVX2 and the widest one the
//! processor runs is chosen at run time. Only loops whose every output element is
//! computed on its own, in the same order of operations whatever the lane count (no
//! sum across elements), belong here: their results are then the same to the bit on
//! every processor, so choosing the width changes the time, never a number.

/// `fn name(args) { body }` compiled three times and dispatched at run time, see the
/// module documentation. The function returns nothing; its arguments are slices and
/// numbers.
macro_rules! widest {
    ($($item:tt)*) => {
        $crate::widest::dispatch!(["avx512f"] ["avx2"] $($item)*);
    };
}

/// [`widest!`] for loops that use `f64::mul_add`: the vector versions also enable FMA,
/// so a fused multiply–add is one instruction. `mul_add` rounds once on every
/// processor (in software where there is no FMA, slowly), so the results are still the
/// same to the bit whichever version runs.
macro_rules! widest_fma {
    ($($item:tt)*) => {
        $crate::widest::dispatch!(["avx512f", "fma"] ["avx2", "fma"] $($item)*);
    };
}

/// The function compiled plain, with the first feature list and with the second, the
/// first whose features the processor has chosen at run time.
macro_rules! dispatch {
    ([$($wide:tt),+] [$($narrow:tt),+]
     $(#[$meta:meta])* $vis:vis fn $name:ident($($arg:ident: $ty:ty),* $(,)?) $body:block) => {
        $(#[$meta])*
        $vis fn $name($($arg: $ty),*) {
            #[inline(always)]
            fn plain($($arg: $ty),*) $body
            #[cfg(target_arch = "x86_64")]
            #[target_feature($(enable = $wide),+)]
            fn avx512($($arg: $ty),*) {
                plain($($arg),*)
            }
            #[cfg(target_arch = "x86_64")]
            #[target_feature($(enable = $narrow),+)]
            fn avx2($($arg: $ty),*) {
                plain($($arg),*)
            }
            #[cfg(target_arch = "x86_64")]
            {
                if $(std::arch::is_x86_feature_detected!($wide))&&+ {
                    // SAFETY: the features were just detected.
                    return unsafe { avx512($($arg),*) };
                }
                if $(std::arch::is_x86_feature_detected!($narrow))&&+ {
                    // SAFETY: the features were just detected.
                    return unsafe { avx2($($arg),*) };
                }
            }
            plain($($arg),*)
        }
    };
}

pub(crate) use {dispatch, widest, widest_fma};
