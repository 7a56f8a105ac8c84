//! Issue 19: `BoundDispatcher` as an engine of its own (test/pack-cloud.py has no collider).
//!
//! The expected boxes are YADE 2023.02a's, printed with `%.17g` by `yade -n -x` on this script:
//!
//! ```text
//! f = Body(); f.shape = Facet(vertices=[<the three vertices below>])
//! f.state.pos = <pos below>; f.state.ori = Quaternion(Vector3(1, 2, 0.5).normalized(), 0.3)
//! O.bodies.append(f); O.bodies.append(sphere(<pos below>, 0.01))
//! s = sphere((1, 1, 1), 0.5); s.bounded = False; O.bodies.append(s)
//! O.engines = [BoundDispatcher([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()])]
//! O.step(); print b.bound.min, b.bound.max (None for the unbounded sphere)
//! ```
// YADE's `%.17g` output kept verbatim (some digits beyond what an f64 needs)
#![allow(clippy::excessive_precision)]

use ryade::io::scene_json;
use serde_json::json;

fn scene(engine: serde_json::Value) -> ryade::scene::Scene {
    let mat = json!({"id": 0, "class": "FrictMat", "young": 1e7, "poisson": 0.3,
                     "frictionAngle": 0.5, "density": 2600, "label": ""});
    let body = |id: usize,
                shape: serde_json::Value,
                pos: [f64; 3],
                ori: [f64; 4],
                bounded: bool| {
        json!({"id": id, "shape": shape, "material": mat, "mask": 1, "bounded": bounded, "pos": pos,
               "vel": [0, 0, 0], "angVel": [0, 0, 0], "ori": ori, "mass": 1.0, "inertia": [1, 1, 1],
               "blockedDOFs": 0, "isDamped": true})
    };
    let v = json!({"format": "ryade-scene-1", "dt": 1e-5, "periodic": false, "bodies": [
        body(0, json!({"class": "Facet", "vertices": [[-0.2, -0.11615239572463147, -0.04227601468247475],
            [0.2, -0.11615239572463147, -0.04227601468247475], [0, 0.25972465258973193, 0.09453204264779275]]}),
            [0.0, -0.07178612843255024, -0.026128013982658994],
            [0.98877107793604235, 0.065220147978391138, 0.13044029595678228, 0.032610073989195569], true),
        body(1, json!({"class": "Sphere", "radius": 0.01}), [0.0, 0.015373308962318154, 0.016238268766993243],
            [1.0, 0.0, 0.0, 0.0], true),
        body(2, json!({"class": "Sphere", "radius": 0.5}), [1.0, 1.0, 1.0], [1.0, 0.0, 0.0, 0.0], false),
    ], "engines": [engine]});
    scene_json::from_value(&v, "bound_dispatcher".into())
        .unwrap()
        .scene
}

#[test]
fn standalone_bound_dispatcher_gives_yades_boxes() {
    let bd = json!({"class": "BoundDispatcher", "bounds": [
        {"class": "Bo1_Sphere_Aabb", "aabbEnlargeFactor": -1.0}, {"class": "Bo1_Facet_Aabb"}]});
    let mut s = scene(bd.clone());
    assert!(s.bodies.bound.iter().all(Option::is_none));
    s.step().unwrap();
    let yade: [[f64; 6]; 2] = [
        [
            -0.19833962384404344,
            -0.19791091550111883,
            -0.13331422215195629,
            0.1871979059680576,
            0.17378845786772684,
            0.10009065526612429,
        ],
        [
            -0.01,
            0.0053733089623181542,
            0.0062382687669932432,
            0.01,
            0.025373308962318153,
            0.026238268766993242,
        ],
    ];
    for (id, want) in yade.iter().enumerate() {
        let b = s.bodies.bound[id]
            .as_ref()
            .expect("a bounded body gets a box");
        let got = [b.min[0], b.min[1], b.min[2], b.max[0], b.max[1], b.max[2]];
        for k in 0..6 {
            assert_eq!(
                got[k].to_bits(),
                want[k].to_bits(),
                "body {id} coord {k}: {got:?} vs YADE {want:?}"
            );
        }
    }
    assert!(
        s.bodies.bound[2].is_none(),
        "an unbounded body gets no box, as in YADE"
    );
    // the engine survives the scene's JSON round trip (O.saveTmp / the compat layer)
    let out = scene_json::to_value(&s, 0);
    assert_eq!(out["engines"][0], bd);
}
