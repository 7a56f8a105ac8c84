//! Cases A and B of shared/yade/core.md §13, built with ryade's own builders (`utils::sphere`,
//! `utils::facet`) and checked bit for bit against the YADE 2023.02a values printed there. This
//! exercises the builders (mass from `pow`, facet inscribed centre) that the golden scene import
//! bypasses.
#![allow(clippy::excessive_precision)]
mod common;

use ryade::math::Vec3;
use ryade::utils;

#[test]
fn case_a_head_on_matches_yade() {
    let mut s = common::scene_with_material(1e-5, 30f64.to_radians());
    let mut a = utils::sphere(Vec3::new(0.0, 0.0, 0.0), 0.01, 0, 2600.0, false);
    a.vel = Vec3::new(0.05, 0.0, 0.0);
    let mut b = utils::sphere(Vec3::new(0.0199, 0.0, 0.0), 0.01, 0, 2600.0, false);
    b.vel = Vec3::new(-0.05, 0.0, 0.0);
    assert_eq!(
        a.mass, 0.010890854532444618,
        "utils.sphere mass as YADE computes it"
    );
    s.bodies.push(a);
    s.bodies.push(b);
    s.engines = common::engines(Vec3::zeros(), 0.0);
    s.step().unwrap();
    assert_eq!(s.time, 1.0000000000000001e-05);
    assert_eq!(s.bodies.pos[0][0], 4.0817984052390713e-07);
    assert_eq!(s.bodies.vel[0][0], 0.040817984052390711);
    assert_eq!(s.forces.force(0)[0], -9.9999999999999396);
    let it = &s.interactions.list[0];
    assert_eq!(it.geom.unwrap().pen, 9.9999999999999395e-05);
    assert_eq!(
        (it.phys.unwrap().kn, it.phys.unwrap().ks),
        (100000.0, 30000.0)
    );
    for _ in 0..4 {
        s.step().unwrap();
    }
    assert_eq!(s.bodies.pos[0][0], 1.110261955188515e-06);
    assert_eq!(s.bodies.pos[1][0], 0.019898889738044816);
    assert_eq!(s.bodies.vel[0][0], 0.0035108336354190053);
    assert_eq!(s.forces.force(1)[0], 10.215030723766464);
    for _ in 5..300 {
        s.step().unwrap();
    }
    assert_eq!(s.time, 0.003000000000000007);
    assert_eq!(
        s.interactions.count_real(),
        0,
        "the spheres separated and the contact was erased"
    );
}

#[test]
fn case_b_facet_sliding_matches_yade() {
    let mut s = common::scene_with_material(1e-5, 30f64.to_radians());
    let mut sp = utils::sphere(Vec3::new(0.0, -0.3, 0.01 - 8e-7), 0.01, 0, 2600.0, false);
    sp.vel = Vec3::new(0.5, 0.0, 0.0);
    s.bodies.push(sp);
    let f = utils::facet(
        [
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::new(1.0, -1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ],
        0,
    )
    .unwrap();
    assert_eq!(
        f.pos[1], -0.38196601125010521,
        "facet body at the inscribed circle centre"
    );
    s.bodies.push(f);
    s.engines = common::engines(Vec3::new(0.0, 0.0, -9.81), 0.0);
    s.step().unwrap();
    let p = s.bodies.pos[0];
    assert_eq!(
        (p[0], p[1], p[2]),
        (
            4.9994345344662341e-06,
            -0.29999999999999999,
            0.009999199998415035
        )
    );
    assert_eq!(s.bodies.ang_vel[0][1], 0.014136072878622757);
    assert_eq!(s.forces.force(0)[0], -0.061584028713594967);
    assert_eq!(s.forces.force(0)[2], 0.1066666666667271);
    assert_eq!(
        s.forces.torque(1)[1],
        0.0012316559406604138,
        "facet torque with the 2R arm quirk"
    );
    let it = &s.interactions.list[0];
    assert_eq!(
        (it.id1, it.id2),
        (1, 0),
        "facet is id1 after the functor swap"
    );
    assert_eq!(it.phys.unwrap().kn, 133333.33333333334);
    for _ in 1..5 {
        s.step().unwrap();
    }
    let p = s.bodies.pos[0];
    assert_eq!(
        (p[0], p[2]),
        (2.4991517977821258e-05, 0.0099991999762933676)
    );
    assert_eq!(s.bodies.vel[0][2], -7.8860693334227967e-07);
    assert_eq!(s.forces.torque(0)[1], 0.00061582783122570523);
    for _ in 5..4000 {
        s.step().unwrap();
    }
    assert_eq!(s.time, 0.040000000000001576);
    assert_eq!(s.interactions.count_real(), 1);
}
