//! ryade: YADE's discrete element core in Rust, matched to YADE 2023.02a bit for bit on small scenes.
//!
//! Data flow of a step (see `scene::Scene::step`): scene -> collider (`bound`, `collider`) ->
//! contact geometry (`geom`) -> contact physics (`phys`) -> law (`law`) -> integrator (`integrator`).
//! Floating-point reductions follow Eigen's order (`math`).

/// `fn NAME / NAME_AVX2 => IMPL(args) -> R`: NAME calls IMPL compiled with AVX2 when the CPU has it
/// (chosen at run time), else IMPL for the baseline target. Neither build lets the compiler contract
/// or reorder floating-point operations, so both give the same bits.
macro_rules! avx2_dispatch {
    ($(#[$m:meta])* fn $name:ident / $avx:ident => $imp:ident ($($a:ident: $t:ty),* $(,)?) $(-> $r:ty)?) => {
        $(#[$m])*
        #[allow(clippy::too_many_arguments)]
        fn $name($($a: $t),*) $(-> $r)? {
            #[cfg(target_arch = "x86_64")]
            if std::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU has AVX2 (checked just above)
                return unsafe { $avx($($a),*) };
            }
            $imp($($a),*)
        }

        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx2")]
        #[allow(clippy::too_many_arguments)]
        unsafe fn $avx($($a: $t),*) $(-> $r)? {
            $imp($($a),*)
        }
    };
}

pub mod bench;
pub mod body;
pub mod bound;
pub mod calibrate;
pub mod cell;
pub mod clump;
pub mod collider;
pub mod dispatch;
pub mod energy;
pub mod fast;
pub mod force_engine;
pub mod forces;
pub mod gap;
pub mod gap_run;
pub mod geogrid;
pub mod geom;
pub mod harness;
pub mod hydro;
pub mod idle_skip;
pub mod integrator;
pub mod interaction;
pub mod io;
pub mod kinematic;
pub mod law;
pub mod material;
pub mod math;
pub mod pack;
pub mod peri_triax;
pub mod phys;
pub mod piston;
pub mod porosity;
pub mod scene;
pub mod shape;
pub mod stdsort;
pub mod timestepper;
pub mod timing;
pub mod triax;
pub mod triax_compression;
pub mod utils;
