fn main() {
    let mut s =
        ryade::io::scene_json::load(std::path::Path::new("bench/scenes/dense8000.scene.json"))
            .unwrap()
            .scene;
    for k in 0..=2000 {
        if k % 250 == 0 || k < 3 {
            let c = s.cell.as_ref().unwrap();
            let mut tr = 0.0;
            for it in &s.interactions.list {
                if let (Some(_), Some(ph)) = (&it.geom, &it.phys) {
                    let l = s.bodies.pos[it.id2 as usize] + c.shift_pos(&it.cell_dist)
                        - s.bodies.pos[it.id1 as usize];
                    tr += (ph.normal_force + ph.shear_force).dot(&l);
                }
            }
            println!(
                "iter {} p {:.1} real {} unb {:.3e}",
                s.iter,
                tr / (3.0 * c.volume()),
                s.interactions.count_real(),
                ryade::utils::unbalanced_force(&s, false)
            );
        }
        s.step().unwrap();
    }
}
