//! Scene pieces shared by the integration tests (each test file includes this module).
#![allow(dead_code)]
use ryade::integrator::Newton;
use ryade::material::FrictMat;
use ryade::math::Vec3;
use ryade::scene::{Engine, Scene};

/// The tests' FrictMat: E = 1e7 Pa, ν = 0.3, ρ = 2600 kg/m³ and the given friction angle (rad).
pub fn frict_mat(friction_angle: f64) -> FrictMat {
    FrictMat {
        id: 0,
        young: 1e7,
        poisson: 0.3,
        density: 2600.0,
        friction_angle,
        ..Default::default()
    }
}

/// YADE's usual engine list for spheres: ForceResetter, InsertionSortCollider, InteractionLoop
/// (default functors: sphere geometry, FrictPhys, Cundall-Strack) and NewtonIntegrator.
pub fn engines(gravity: Vec3, damping: f64) -> Vec<Engine> {
    vec![
        Engine::ForceResetter,
        Engine::Collider(Box::default()),
        Engine::InteractionLoop(Box::default()),
        Engine::Newton(Box::new(Newton {
            damping,
            gravity,
            ..Default::default()
        })),
    ]
}

/// An empty scene with time step `dt` and the tests' material of friction angle `friction_angle`.
pub fn scene_with_material(dt: f64, friction_angle: f64) -> Scene {
    let mut s = Scene {
        dt,
        ..Default::default()
    };
    s.materials.push(frict_mat(friction_angle));
    s
}
