//! ryade: YADE's discrete element core in Rust, matched to YADE 2023.02a bit for bit on small scenes.
//!
//! Data flow of a step (see `scene::Scene::step`): scene -> collider (`bound`, `collider`) ->
//! contact geometry (`geom`) -> contact physics (`phys`) -> law (`law`) -> integrator (`integrator`).
//! Floating-point reductions follow Eigen's order (`math`).

pub mod bench;
pub mod body;
pub mod bound;
pub mod calibrate;
pub mod cell;
pub mod clump;
pub mod collider;
pub mod dispatch;
pub mod fast;
pub mod forces;
pub mod gap;
pub mod gap_run;
pub mod geogrid;
pub mod geom;
pub mod harness;
pub mod idle_skip;
pub mod integrator;
pub mod interaction;
pub mod io;
pub mod kinematic;
pub mod law;
pub mod material;
pub mod math;
pub mod pack;
pub mod phys;
pub mod porosity;
pub mod scene;
pub mod shape;
pub mod stdsort;
pub mod timestepper;
pub mod utils;
