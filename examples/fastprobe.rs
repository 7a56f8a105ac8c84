use ryade::fast::{FastOptions, FastSim};
fn cpu() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .unwrap()
        .split_whitespace()
        .next()
        .unwrap()
        .parse::<f64>()
        .unwrap()
        * 1e-9
}
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
    let skin: f64 = std::env::args()
        .nth(4)
        .map(|s| s.parse().unwrap())
        .unwrap_or(0.3);
    let s0 = ryade::io::scene_json::load(std::path::Path::new(&p))
        .unwrap()
        .scene;
    let mut y = s0.clone();
    let t = cpu();
    for _ in 0..n {
        y.step().unwrap();
    }
    let ty = cpu() - t;
    let mut f = FastSim::from_scene(&s0, FastOptions { threads, skin }).unwrap();
    let t = cpu();
    let w = std::time::Instant::now();
    f.run(n);
    let tf = cpu() - t;
    let wf = w.elapsed().as_secs_f64();
    let mut s = s0.clone();
    f.write_back(&mut s);
    let nb = s.bodies.len() as f64;
    println!("yade-order: {:.3e} ps/s (cpu)  fast: {:.3e} ps/s (cpu {:.3}s) {:.3e} (wall), rebuilds {} pairs {} contacts {} (yade {})",
        n as f64 * nb / ty, n as f64 * nb / tf, tf, n as f64 * nb / wf, f.rebuilds, f.pairs(), f.active_contacts(), y.interactions.count_real());
    let mut md: f64 = 0.0;
    let mut mv: f64 = 0.0;
    let mut vs: f64 = 0.0;
    for i in 0..s.bodies.len() {
        md = md.max((s.bodies.pos[i] - y.bodies.pos[i]).norm());
        mv = mv.max((s.bodies.vel[i] - y.bodies.vel[i]).norm());
        vs = vs.max(y.bodies.vel[i].norm());
    }
    println!(
        "max |dpos| {:.3e}  max |dvel| {:.3e} (max |vel| {:.3e})",
        md, mv, vs
    );
    println!(
        "unbalanced yade {:.6e} fast {:.6e}; Ek yade {:.6e} fast {:.6e}",
        ryade::utils::unbalanced_force(&y, false),
        ryade::utils::unbalanced_force(&s, false),
        ryade::utils::kinetic_energy(&y),
        ryade::utils::kinetic_energy(&s)
    );
    println!("{:?}", f.memory());
    println!(
        "{:?} per step ms: contacts {:.3} newton {:.3}",
        f.timing,
        1e3 * f.timing.contacts / n as f64,
        1e3 * f.timing.newton / n as f64
    );
}
