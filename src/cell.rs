//! The periodic cell (YADE `core/Cell.{hpp,cpp}`). Always 3-D periodic; positions are never wrapped.

use crate::math::{mat_mul, mat_vec, mat_vec_i, norm, Mat3, Vec3};

#[derive(Clone, Debug)]
pub struct Cell {
    /// Columns are the cell base vectors.
    pub hsize: Mat3,
    pub prev_hsize: Mat3,
    pub trsf: Mat3,
    pub vel_grad: Mat3,
    pub next_vel_grad: Mat3,
    pub vel_grad_changed: bool,
    pub prev_vel_grad: Mat3,
    /// 0: no homothetic terms, 1: position only, 2 (YADE default): position and velocity.
    pub homo_deform: i32,
    size: Vec3,
    unshear: Mat3,
    has_shear: bool,
    vgrad_times_prev_h: Mat3,
}

impl Cell {
    /// `O.periodic=True` then `O.cell.setBox(...)` or `O.cell.hSize=...`.
    pub fn new(hsize: Mat3) -> Result<Cell, String> {
        let mut c = Cell {
            hsize,
            prev_hsize: hsize,
            trsf: Mat3::identity(),
            vel_grad: Mat3::zeros(),
            next_vel_grad: Mat3::zeros(),
            vel_grad_changed: false,
            prev_vel_grad: Mat3::zeros(),
            homo_deform: 2,
            size: Vec3::zeros(),
            unshear: Mat3::identity(),
            has_shear: false,
            vgrad_times_prev_h: Mat3::zeros(),
        };
        c.integrate_and_update(0.0)?;
        Ok(c)
    }

    pub fn set_box(size: Vec3) -> Result<Cell, String> {
        Cell::new(Mat3::from_diagonal(&size))
    }

    /// Mirrors `Cell::integrateAndUpdate` (core/Cell.cpp), run at the start of every step.
    pub fn integrate_and_update(&mut self, dt: f64) -> Result<(), String> {
        let trsf_inc = self.vel_grad * dt;
        self.trsf += mat_mul(&trsf_inc, &self.trsf);
        self.prev_hsize = self.hsize;
        self.vgrad_times_prev_h = mat_mul(&self.vel_grad, &self.prev_hsize);
        self.hsize += mat_mul(&trsf_inc, &self.hsize);
        if self.hsize.determinant() == 0.0 {
            return Err("Cell is degenerate (zero volume): check O.cell.hSize / velGrad".into());
        }
        let mut hnorm = Mat3::zeros();
        for i in 0..3 {
            let base: Vec3 = self.hsize.column(i).into();
            self.size[i] = norm(&base);
            for r in 0..3 {
                hnorm[(r, i)] = base[r] / self.size[i];
            }
        }
        let h = &self.hsize;
        self.has_shear = h[(0, 1)] != 0.0
            || h[(0, 2)] != 0.0
            || h[(1, 0)] != 0.0
            || h[(1, 2)] != 0.0
            || h[(2, 0)] != 0.0
            || h[(2, 1)] != 0.0;
        self.unshear = hnorm
            .try_inverse()
            .ok_or_else(|| "Cell base vectors are degenerate".to_string())?;
        Ok(())
    }

    /// Lengths of the base vectors (`Cell.size`).
    pub fn size(&self) -> Vec3 {
        self.size
    }

    pub fn has_shear(&self) -> bool {
        self.has_shear
    }

    pub fn volume(&self) -> f64 {
        self.hsize.determinant()
    }

    /// `Cell::unshearPt`: a matrix product even for a box cell (YADE evaluates it; identity rows keep
    /// values except that -0 becomes +0).
    pub fn unshear_pt(&self, p: &Vec3) -> Vec3 {
        mat_vec(&self.unshear, p)
    }

    /// `Cell::intrShiftPos`: `hSize * cellDist`.
    #[inline(always)]
    pub fn shift_pos(&self, cell_dist: &[i32; 3]) -> Vec3 {
        mat_vec_i(&self.hsize, cell_dist)
    }

    /// `Cell::intrShiftVel`: `(velGrad * prevHSize) * cellDist`.
    #[inline(always)]
    pub fn shift_vel(&self, cell_dist: &[i32; 3]) -> Vec3 {
        mat_vec_i(&self.vgrad_times_prev_h, cell_dist)
    }

    /// `Cell::wrapPt` for a box cell: each coordinate into [0, size).
    pub fn wrap_pt(&self, p: &Vec3) -> Vec3 {
        let mut r = *p;
        for i in 0..3 {
            let n = p[i] / self.size[i];
            r[i] = (n - n.floor()) * self.size[i];
        }
        r
    }
}
