use ryade::fast::{FastOptions, FastSim};
fn main() {
    let p = std::env::args().nth(1).unwrap();
    let n: u64 = std::env::args()
        .nth(2)
        .map(|s| s.parse().unwrap())
        .unwrap_or(200);
    let threads: usize = std::env::args()
        .nth(3)
        .map(|s| s.parse().unwrap())
        .unwrap_or(1);
    let s0 = ryade::io::scene_json::load(std::path::Path::new(&p))
        .unwrap()
        .scene;
    let mut f = FastSim::from_scene(
        &s0,
        FastOptions {
            threads,
            ..Default::default()
        },
    )
    .unwrap();
    f.run(n);
    println!("{}", f.active_contacts());
}
