//! Triaxial (TX-type) geogrid layout: a periodic lattice of equilateral triangles, optionally with an
//! articulated node at mid-rib (the paper's rib model, seed-paper.txt 2.1), as node positions and
//! ribs (node pairs with the periodic `cellDist` of node 2) ready for `gridNode`/`gridConnection`.
//!
//! Lattice (shared/study.md "Geogrid"): `2*ny` rows of `nx` junctions, junction (i, j) at
//! `x = (i + 1/4 + (j mod 2)/2)·a`, `y = (j + 1/2)·a·√3/2`; each junction is linked to (i+1, j) and to
//! its two neighbours in row j+1, so every junction has 6 ribs and the cell `nx·a × ny·a·√3` tiles
//! the plane. YADE keeps one interaction per body pair, so a periodic lattice needs at least 3
//! junctions per period along x and 2 rectangular periods along y (otherwise two ribs would join the
//! same pair of nodes).

use crate::math::Vec3;

/// Parameters of a triaxial geogrid layer.
#[derive(Clone, Debug, PartialEq)]
pub struct TriaxialGrid {
    /// Rib length between junctions [m] (study default 0.06, TX-type grid).
    pub a: f64,
    /// Junctions per row (lattice periods along x).
    pub nx: usize,
    /// Rectangular periods along y (2 rows each).
    pub ny: usize,
    /// Height of the grid plane.
    pub z: f64,
    /// Insert an articulated node at the middle of every rib.
    pub mid_rib_nodes: bool,
}

impl Default for TriaxialGrid {
    fn default() -> Self {
        TriaxialGrid {
            a: 0.06,
            nx: 3,
            ny: 2,
            z: 0.0,
            mid_rib_nodes: false,
        }
    }
}

/// One connection: node indices and the period of node 2 relative to node 1 (`gridConnection(...,
/// cellDist=...)`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rib {
    pub node1: usize,
    pub node2: usize,
    pub cell_dist: [i32; 3],
}

#[derive(Clone, Debug, PartialEq)]
pub struct GridLayout {
    pub nodes: Vec<Vec3>,
    /// True for lattice junctions, false for mid-rib nodes.
    pub junction: Vec<bool>,
    pub ribs: Vec<Rib>,
    /// Cell size in x and y (z is up to the scene).
    pub cell_xy: (f64, f64),
}

/// Rib (and node) radius of a cylinder with the cross-section area of the physical rib.
pub fn rib_radius_from_area(area: f64) -> f64 {
    (area / std::f64::consts::PI).sqrt()
}

impl TriaxialGrid {
    pub fn cell_xy(&self) -> (f64, f64) {
        (
            self.nx as f64 * self.a,
            self.ny as f64 * self.a * 3f64.sqrt(),
        )
    }

    /// Build the layout; errors name the parameter to change.
    pub fn build(&self) -> Result<GridLayout, String> {
        if !(self.a > 0.0 && self.a.is_finite()) {
            return Err(format!("rib length a = {} must be positive", self.a));
        }
        if self.nx < 3 || self.ny < 2 {
            return Err(format!(
                "a periodic triaxial grid needs nx >= 3 and ny >= 2 (got nx={}, ny={}): with fewer periods two \
                 ribs would join the same pair of nodes, which YADE's one-interaction-per-pair cannot hold",
                self.nx, self.ny
            ));
        }
        let rows = 2 * self.ny;
        let pitch = self.a * 3f64.sqrt() / 2.0;
        let idx = |i: usize, j: usize| j * self.nx + i;
        let mut nodes = Vec::with_capacity(self.nx * rows);
        for j in 0..rows {
            for i in 0..self.nx {
                let x = (i as f64 + 0.25 + 0.5 * (j % 2) as f64) * self.a;
                nodes.push(Vec3::new(x, (j as f64 + 0.5) * pitch, self.z));
            }
        }
        let mut junction_ribs = Vec::with_capacity(3 * nodes.len());
        let wrap = |k: i64, n: usize| -> (usize, i32) {
            let n = n as i64;
            (k.rem_euclid(n) as usize, k.div_euclid(n) as i32)
        };
        for j in 0..rows {
            for i in 0..self.nx {
                let (i1, cx) = wrap(i as i64 + 1, self.nx);
                junction_ribs.push(Rib {
                    node1: idx(i, j),
                    node2: idx(i1, j),
                    cell_dist: [cx, 0, 0],
                });
                let (jn, cy) = wrap(j as i64 + 1, rows);
                // row j+1 is shifted by +a/2 (j even) or -a/2 (j odd) relative to row j
                let pair = if j % 2 == 0 {
                    [i as i64 - 1, i as i64]
                } else {
                    [i as i64, i as i64 + 1]
                };
                for inb in pair {
                    let (iw, cx) = wrap(inb, self.nx);
                    junction_ribs.push(Rib {
                        node1: idx(i, j),
                        node2: idx(iw, jn),
                        cell_dist: [cx, cy, 0],
                    });
                }
            }
        }
        let mut junction = vec![true; nodes.len()];
        let (lx, ly) = self.cell_xy();
        let ribs = if !self.mid_rib_nodes {
            junction_ribs
        } else {
            let mut out = Vec::with_capacity(2 * junction_ribs.len());
            for r in junction_ribs {
                let p2 = nodes[r.node2]
                    + Vec3::new(r.cell_dist[0] as f64 * lx, r.cell_dist[1] as f64 * ly, 0.0);
                let m = (nodes[r.node1] + p2) * 0.5;
                nodes.push(m);
                junction.push(false);
                let mid = nodes.len() - 1;
                out.push(Rib {
                    node1: r.node1,
                    node2: mid,
                    cell_dist: [0, 0, 0],
                });
                out.push(Rib {
                    node1: mid,
                    node2: r.node2,
                    cell_dist: r.cell_dist,
                });
            }
            out
        };
        Ok(GridLayout {
            nodes,
            junction,
            ribs,
            cell_xy: (lx, ly),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    fn rib_vec(g: &GridLayout, r: &Rib) -> Vec3 {
        g.nodes[r.node2]
            + Vec3::new(
                r.cell_dist[0] as f64 * g.cell_xy.0,
                r.cell_dist[1] as f64 * g.cell_xy.1,
                0.0,
            )
            - g.nodes[r.node1]
    }

    /// The study's sizes (study.md): tiny 12 nodes/36 ribs, medium 30/90, full 120/360.
    #[test]
    fn counts_match_the_study() {
        for (nx, ny, n, r) in [
            (3, 2, 12, 36),
            (4, 2, 16, 48),
            (5, 3, 30, 90),
            (10, 6, 120, 360),
        ] {
            let g = TriaxialGrid {
                nx,
                ny,
                ..Default::default()
            }
            .build()
            .unwrap();
            assert_eq!((g.nodes.len(), g.ribs.len()), (n, r));
        }
    }

    /// Every rib is a lattice edge of length a in one of the three directions 0°, 60°, 120°; every
    /// junction has six ribs; no two ribs join the same pair (YADE's one interaction per pair).
    #[test]
    fn equilateral_periodic_lattice() {
        let g = TriaxialGrid {
            nx: 5,
            ny: 3,
            a: 0.06,
            ..Default::default()
        }
        .build()
        .unwrap();
        let mut degree = vec![0; g.nodes.len()];
        let mut pairs = HashSet::new();
        for r in &g.ribs {
            let d = rib_vec(&g, r);
            assert!((d.norm() - 0.06).abs() < 1e-12, "rib length {}", d.norm());
            let ang = d[1].atan2(d[0]).to_degrees().rem_euclid(180.0);
            assert!(
                [0.0, 60.0, 120.0].iter().any(|x| (ang - x).abs() < 1e-9),
                "angle {}",
                ang
            );
            degree[r.node1] += 1;
            degree[r.node2] += 1;
            assert!(
                pairs.insert((r.node1.min(r.node2), r.node1.max(r.node2))),
                "duplicate pair"
            );
        }
        assert!(degree.iter().all(|&d| d == 6));
        // the cell is a whole number of lattice periods: all nodes inside it
        assert!(g
            .nodes
            .iter()
            .all(|p| p[0] > 0.0 && p[0] < g.cell_xy.0 && p[1] > 0.0 && p[1] < g.cell_xy.1));
    }

    #[test]
    fn mid_rib_nodes_split_every_rib() {
        let g = TriaxialGrid {
            mid_rib_nodes: true,
            ..Default::default()
        }
        .build()
        .unwrap();
        assert_eq!(g.nodes.len(), 12 + 36);
        assert_eq!(g.ribs.len(), 72);
        for r in &g.ribs {
            assert!((rib_vec(&g, r).norm() - 0.03).abs() < 1e-12);
        }
        assert_eq!(g.junction.iter().filter(|j| !**j).count(), 36);
    }

    #[test]
    fn too_small_lattices_are_refused_with_a_reason() {
        let e = TriaxialGrid {
            nx: 2,
            ..Default::default()
        }
        .build()
        .unwrap_err();
        assert!(e.contains("nx >= 3"));
    }

    #[test]
    fn rib_radius_keeps_the_area() {
        let r = rib_radius_from_area(1.2566370614359173e-5);
        assert!((r - 0.002).abs() < 1e-15);
    }
}
