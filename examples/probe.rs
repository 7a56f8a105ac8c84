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
struct Instant(f64);
impl Instant {
    fn now() -> Instant {
        Instant(cpu())
    }
    fn elapsed(&self) -> std::time::Duration {
        std::time::Duration::from_secs_f64(cpu() - self.0)
    }
}
fn main() {
    let p = std::env::args().nth(1).unwrap();
    let n: usize = std::env::args()
        .nth(2)
        .map(|s| s.parse().unwrap())
        .unwrap_or(500);
    let mut s = ryade::io::scene_json::load(std::path::Path::new(&p))
        .unwrap()
        .scene;
    for _ in 0..20 {
        s.step().unwrap();
    }
    let ne = s.engines.len();
    let mut t = vec![0f64; ne];
    let t0 = Instant::now();
    for _ in 0..n {
        s.step_prologue().unwrap();
        for k in 0..ne {
            let a = Instant::now();
            s.run_engine(k).unwrap();
            t[k] += a.elapsed().as_secs_f64();
        }
        s.step_epilogue();
    }
    let tot = t0.elapsed().as_secs_f64();
    println!(
        "total {:.3}s  {:.3e} particle-steps/s",
        tot,
        (n * s.bodies.len()) as f64 / tot
    );
    for k in 0..ne {
        println!(
            "{:24} {:.3} ms/step",
            s.engines[k].class_name(),
            1e3 * t[k] / n as f64
        );
    }
    let h: u64 = s
        .bodies
        .pos
        .iter()
        .chain(s.bodies.vel.iter())
        .flat_map(|v| v.iter())
        .fold(0u64, |a, x| a.rotate_left(5) ^ x.to_bits());
    println!(
        "idle {}",
        s.interactions.scan.iter().filter(|e| e.idle).count()
    );
    println!(
        "hash {:016x} iter {} list {} real {}",
        h,
        s.iter,
        s.interactions.list.len(),
        s.interactions.count_real()
    );
}
