//! Where a step's time goes, by thread CPU time (robust on a shared machine):
//! `cargo run --release --example step_profile -- SCENE.json [STEPS] [THREADS]`.
//! Prints the YADE-order path (THREADS threads, same bits) per engine and the fast path per phase, with particle-steps/s.

use ryade::fast::{FastOptions, FastSim};

/// CPU seconds of this thread.
fn cpu() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(0.0, |ns| ns * 1e-9)
}

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args.next().expect("SCENE.json");
    let n: u64 = args.next().map_or(500, |s| s.parse().unwrap());
    let threads: usize = args.next().map_or(1, |s| s.parse().unwrap());
    let skin: f64 = args
        .next()
        .map_or(FastOptions::default().skin, |s| s.parse().unwrap());
    let s0 = ryade::io::scene_json::load(std::path::Path::new(&path))
        .unwrap()
        .scene;
    let nb = s0.bodies.len() as f64;
    let mut s = s0.clone();
    s.threads = threads;
    for _ in 0..20 {
        s.step().unwrap();
    }
    let mut per_engine = vec![0.0; s.engines.len()];
    let w0 = std::time::Instant::now();
    let t0 = cpu();
    for _ in 0..n {
        s.step_prologue().unwrap();
        for (k, t) in per_engine.iter_mut().enumerate() {
            let a = cpu();
            s.run_engine(k).unwrap();
            *t += cpu() - a;
        }
        s.step_epilogue();
    }
    let total = cpu() - t0;
    let wall = w0.elapsed().as_secs_f64();
    println!(
        "YADE-order path ({} threads): {:.3e} particle-steps/s (main thread CPU), {:.3e} (wall)",
        threads,
        n as f64 * nb / total,
        n as f64 * nb / wall
    );
    for (e, t) in s.engines.iter().zip(&per_engine) {
        println!("  {:24} {:.3} ms/step", e.class_name(), 1e3 * t / n as f64);
    }
    let opt = FastOptions { threads, skin };
    let mut f = FastSim::from_scene(&s0, opt).unwrap();
    f.run(20);
    let (t0, w0) = (cpu(), std::time::Instant::now());
    let before = f.timing;
    f.run(n);
    let (tc, tw) = (cpu() - t0, w0.elapsed().as_secs_f64());
    println!(
        "fast path ({} threads): {:.3e} particle-steps/s (main thread CPU), {:.3e} (wall); {} pairs, {} contacts, {} list builds",
        threads,
        n as f64 * nb / tc,
        n as f64 * nb / tw,
        f.pairs(),
        f.active_contacts(),
        f.rebuilds
    );
    let ms = |a: f64, b: f64| 1e3 * (a - b) / n as f64;
    println!(
        "  contacts {:.3} ms/step, integration {:.3} ms/step, list builds {:.3} ms/step (wall)",
        ms(f.timing.contacts, before.contacts),
        ms(f.timing.newton, before.newton),
        ms(f.timing.rebuild, before.rebuild)
    );
}
