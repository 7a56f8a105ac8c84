//! Body shapes: Sphere, Facet, Wall, Box (YADE `pkg/common/{Sphere,Facet,Wall,Box}.hpp`) and the grid
//! shapes GridNode and GridConnection (`pkg/common/Grid.hpp`), which both derive from Sphere in YADE:
//! functor dispatch, `PWaveTimeStep` and the collider's minimum radius treat them as spheres.

use crate::math::{cross, norm, normalized, Vec3};

/// A triangle with the data YADE precomputes in `Facet::postLoad` (`pkg/common/Facet.cpp`).
#[derive(Clone, Debug, PartialEq)]
pub struct Facet {
    /// Vertices relative to the body position (YADE stores them local).
    pub vertices: [Vec3; 3],
    pub normal: Vec3,
    pub area: f64,
    /// Unit in-plane edge normals, pointing out of the triangle.
    pub ne: [Vec3; 3],
    /// Vertex distances from the centre and unit vectors towards them.
    pub vl: [f64; 3],
    pub vu: [Vec3; 3],
    /// Inscribed circle radius.
    pub icr: f64,
}

impl Facet {
    /// Mirrors `Facet::postLoad` (pkg/common/Facet.cpp), in its evaluation order.
    pub fn new(vertices: [Vec3; 3]) -> Result<Facet, String> {
        let e = [
            vertices[1] - vertices[0],
            vertices[2] - vertices[1],
            vertices[0] - vertices[2],
        ];
        for (i, ei) in e.iter().enumerate() {
            if crate::math::norm2(ei) == 0.0 {
                return Err(format!(
                    "facet has coincident vertices {} and {}",
                    i,
                    (i + 1) % 3
                ));
            }
        }
        let mut normal = cross(&e[0], &e[1]);
        let area = 0.5 * norm(&normal);
        let two_area = 2.0 * area;
        normal = Vec3::new(
            normal[0] / two_area,
            normal[1] / two_area,
            normal[2] / two_area,
        );
        let mut ne = [Vec3::zeros(); 3];
        let mut vl = [0.0; 3];
        let mut vu = [Vec3::zeros(); 3];
        for i in 0..3 {
            ne[i] = normalized(&cross(&e[i], &normal));
            vl[i] = norm(&vertices[i]);
            vu[i] = Vec3::new(
                vertices[i][0] / vl[i],
                vertices[i][1] / vl[i],
                vertices[i][2] / vl[i],
            );
        }
        let p = norm(&e[0]) + norm(&e[1]) + norm(&e[2]);
        let icr = norm(&e[0]) * crate::math::dot(&ne[0], &e[2]) / p;
        Ok(Facet {
            vertices,
            normal,
            area,
            ne,
            vl,
            vu,
            icr,
        })
    }
}

/// `GridNode` (pkg/common/Grid.hpp): a sphere-like vertex of a grid, with the list of the
/// GridConnection bodies attached to it (`ConnList`, in `addConnection` order).
#[derive(Clone, Debug, PartialEq)]
pub struct GridNode {
    pub radius: f64,
    pub conn_list: Vec<u32>,
}

/// `GridConnection` (pkg/common/Grid.hpp): a cylinder between two GridNode bodies. `cell_dist` is
/// the period of node 2 relative to node 1 when `periodic`.
#[derive(Clone, Debug, PartialEq)]
pub struct GridConnection {
    pub radius: f64,
    pub node1: u32,
    pub node2: u32,
    pub periodic: bool,
    pub cell_dist: [i32; 3],
}

#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    Sphere {
        radius: f64,
    },
    Facet(Box<Facet>),
    /// Infinite plane normal to `axis`; `sense` -1, 0 (both sides) or 1.
    Wall {
        axis: usize,
        sense: i32,
    },
    /// Oriented box with half-sizes `extents`.
    Box {
        extents: Vec3,
    },
    GridNode(Box<GridNode>),
    GridConnection(Box<GridConnection>),
    /// A rigid aggregate of member bodies (core/Clump.hpp); never bounded, never in contact.
    Clump(Box<crate::clump::Clump>),
}

impl Shape {
    /// A connection of radius `r` between nodes `n1` and `n2`, not periodic (for tests).
    #[cfg(test)]
    pub(crate) fn connection(r: f64, n1: u32, n2: u32) -> Shape {
        Shape::GridConnection(Box::new(GridConnection {
            radius: r,
            node1: n1,
            node2: n2,
            periodic: false,
            cell_dist: [0; 3],
        }))
    }

    pub fn class_name(&self) -> &'static str {
        match self {
            Shape::Sphere { .. } => "Sphere",
            Shape::Facet(_) => "Facet",
            Shape::Wall { .. } => "Wall",
            Shape::Box { .. } => "Box",
            Shape::GridNode(_) => "GridNode",
            Shape::GridConnection(_) => "GridConnection",
            Shape::Clump(_) => "Clump",
        }
    }

    /// The radius of a shape that "is a" Sphere in YADE's class hierarchy (`dynamic_cast<Sphere*>`):
    /// Sphere, GridNode and GridConnection.
    pub fn sphere_radius(&self) -> Option<f64> {
        match self {
            Shape::Sphere { radius } => Some(*radius),
            Shape::GridNode(n) => Some(n.radius),
            Shape::GridConnection(c) => Some(c.radius),
            _ => None,
        }
    }

    /// The radius of a plain `Sphere` only.
    pub fn plain_sphere_radius(&self) -> Option<f64> {
        match self {
            Shape::Sphere { radius } => Some(*radius),
            _ => None,
        }
    }
}

/// Shape classes for functor dispatch (YADE's `Shape` hierarchy: the grid shapes derive from Sphere).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShapeClass {
    Shape,
    Sphere,
    GridNode,
    GridConnection,
    Facet,
    Wall,
    Box,
    Clump,
}

impl crate::dispatch::Hierarchy for ShapeClass {
    fn parent(self) -> Option<Self> {
        match self {
            ShapeClass::Shape => None,
            ShapeClass::GridNode | ShapeClass::GridConnection => Some(ShapeClass::Sphere),
            _ => Some(ShapeClass::Shape),
        }
    }
}

impl Shape {
    pub fn class(&self) -> ShapeClass {
        match self {
            Shape::Sphere { .. } => ShapeClass::Sphere,
            Shape::Facet(_) => ShapeClass::Facet,
            Shape::Wall { .. } => ShapeClass::Wall,
            Shape::Box { .. } => ShapeClass::Box,
            Shape::GridNode(_) => ShapeClass::GridNode,
            Shape::GridConnection(_) => ShapeClass::GridConnection,
            Shape::Clump(_) => ShapeClass::Clump,
        }
    }
}
