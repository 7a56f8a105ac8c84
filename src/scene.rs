//! The scene and its time step (YADE `core/Scene.cpp::moveToNextTimeStep`).
//!
//! Data flow of one step, each stage in its own module and given its state explicitly:
//! `ForceResetter` (forces) -> `collider` (bound, collider) -> `InteractionLoop` (geom -> phys ->
//! law) -> `integrator` (Newton). Engines run in list order, as in `O.engines`.

use crate::body::Bodies;
use crate::cell::Cell;
use crate::collider::{Collider, ColliderCtx};
use crate::forces::Forces;
use crate::geom::{self, GeomCtx, Kin, Pair};
use crate::integrator::{Newton, NewtonError};
use crate::interaction::{GeomFunctor, Interactions};
use crate::law::{self, LawBodies, LawEnergy};
use crate::material::FrictMat;
use crate::math::Vec3;
use crate::phys;
use crate::shape::Shape;

/// The functor lists of an `InteractionLoop`.
#[derive(Clone, Debug, PartialEq)]
pub struct InteractionLoop {
    pub sphere_sphere: Option<geom::sphere_sphere::Params>,
    pub facet_sphere: Option<geom::facet_sphere::Params>,
    pub wall_sphere: Option<geom::wall_sphere::Params>,
    pub box_sphere: Option<geom::box_sphere::Params>,
    /// `Ip2_FrictMat_FrictMat_FrictPhys` present.
    pub frict_phys: bool,
    /// `Law2_ScGeom_FrictPhys_CundallStrack` and its parameters.
    pub cundall_strack: Option<law::Params>,
}

impl Default for InteractionLoop {
    /// YADE's default functor lists: sphere-sphere, facet-sphere, box-sphere; FrictPhys; Cundall-Strack.
    fn default() -> Self {
        InteractionLoop {
            sphere_sphere: Some(Default::default()),
            facet_sphere: Some(Default::default()),
            wall_sphere: None,
            box_sphere: Some(Default::default()),
            frict_phys: true,
            cundall_strack: Some(Default::default()),
        }
    }
}

#[derive(Clone, Debug)]
pub enum Engine {
    ForceResetter,
    Collider(Box<Collider>),
    InteractionLoop(Box<InteractionLoop>),
    Newton(Box<Newton>),
    TimeStepper(Box<crate::timestepper::GlobalStiffnessTimeStepper>),
    /// An engine run outside the core (e.g. a Python `PyRunner`): the step calls the hook given to
    /// `Scene::step_with` with this id, at this position in the engine list.
    External(u32),
}

impl Engine {
    pub fn class_name(&self) -> &'static str {
        match self {
            Engine::ForceResetter => "ForceResetter",
            Engine::Collider(_) => "InsertionSortCollider",
            Engine::InteractionLoop(_) => "InteractionLoop",
            Engine::Newton(_) => "NewtonIntegrator",
            Engine::TimeStepper(_) => "GlobalStiffnessTimeStepper",
            Engine::External(_) => "External",
        }
    }
}

/// Why a step stopped. Carries what a user needs to fix it.
#[derive(Debug, Clone, thiserror::Error)]
pub enum StepError {
    #[error("step {iter}: body #{id} has a non-finite {what}. Likely cause: the time step {dt:e} s is above the critical one ({crit}); lower O.dt (e.g. 0.5*PWaveTimeStep()) or check stiffness and masses")]
    NonFinite {
        iter: i64,
        id: usize,
        what: &'static str,
        dt: f64,
        crit: String,
    },
    #[error("step {iter}: {msg}")]
    Engine { iter: i64, msg: String },
}

/// Energy bookkeeping (`O.trackEnergy`): the terms this engine's laws produce.
#[derive(Clone, Debug, Default)]
pub struct Energy {
    pub plast_dissip: f64,
    pub elast_potential: f64,
}

#[derive(Clone, Debug)]
pub struct Scene {
    pub bodies: Bodies,
    pub materials: Vec<FrictMat>,
    pub interactions: Interactions,
    pub forces: Forces,
    pub cell: Option<Cell>,
    pub engines: Vec<Engine>,
    /// `Engine.dead` per engine (missing entries are alive); dead engines are skipped.
    pub engine_dead: Vec<bool>,
    pub dt: f64,
    pub iter: i64,
    pub time: f64,
    pub track_energy: bool,
    pub energy: Energy,
}

impl Default for Scene {
    fn default() -> Self {
        Scene {
            bodies: Bodies::default(),
            materials: Vec::new(),
            interactions: Interactions::default(),
            forces: Forces::default(),
            cell: None,
            engines: Vec::new(),
            engine_dead: Vec::new(),
            dt: 1e-8,
            iter: 0,
            time: 0.0,
            track_energy: false,
            energy: Energy::default(),
        }
    }
}

impl Scene {
    pub fn periodic(&self) -> bool {
        self.cell.is_some()
    }

    pub fn newton(&self) -> Option<&Newton> {
        self.engines.iter().find_map(|e| match e {
            Engine::Newton(n) => Some(n.as_ref()),
            _ => None,
        })
    }

    /// `O.step()`: cell update, every engine in order, then `iter += 1` and `time += dt`. A scene with
    /// `External` engines must be stepped with `step_with`.
    pub fn step(&mut self) -> Result<(), StepError> {
        self.step_with(&mut |id, s: &mut Scene| {
            Err(format!(
                "external engine {} has no runner (at iteration {})",
                id, s.iter
            ))
        })
    }

    /// One step; `hook(id, scene)` runs each `Engine::External(id)` with full access to the scene.
    pub fn step_with(
        &mut self,
        hook: &mut dyn FnMut(u32, &mut Scene) -> Result<(), String>,
    ) -> Result<(), StepError> {
        self.step_prologue()?;
        let mut k = 0;
        while k < self.engines.len() {
            if !self.is_dead(k) {
                if let Engine::External(id) = self.engines[k] {
                    let iter = self.iter;
                    hook(id, self).map_err(|msg| StepError::Engine { iter, msg })?;
                } else {
                    self.run_engine(k)?;
                }
            }
            k += 1;
        }
        self.step_epilogue();
        Ok(())
    }

    /// First part of a step (`Cell::integrateAndUpdate` in a periodic scene). A caller that drives the
    /// engines itself runs `step_prologue`, then `run_engine(k)` for each live engine in order, then
    /// `step_epilogue`.
    pub fn step_prologue(&mut self) -> Result<(), StepError> {
        let iter = self.iter;
        if let Some(c) = self.cell.as_mut() {
            c.integrate_and_update(self.dt)
                .map_err(|msg| StepError::Engine { iter, msg })?;
        }
        Ok(())
    }

    /// Last part of a step: `iter += 1`, `time += dt` (a running sum, as YADE).
    pub fn step_epilogue(&mut self) {
        self.iter += 1;
        self.time += self.dt;
    }

    /// Whether engine `k` is marked dead.
    pub fn is_dead(&self, k: usize) -> bool {
        self.engine_dead.get(k).copied().unwrap_or(false)
    }

    /// Run the built-in engine at position `k` (an `External` one is a no-op here).
    pub fn run_engine(&mut self, k: usize) -> Result<(), StepError> {
        let iter = self.iter;
        let err = |msg: String| StepError::Engine { iter, msg };
        let newton_indicator = self.newton().map(|n| n.max_velocity_sq);
        let mut e = std::mem::replace(&mut self.engines[k], Engine::External(u32::MAX));
        let r = match &mut e {
            Engine::ForceResetter => {
                self.forces.reset(self.bodies.len(), self.iter);
                if self.track_energy {
                    self.energy.elast_potential = 0.0;
                }
                Ok(())
            }
            Engine::Collider(c) => {
                if c.is_activated(self.bodies.len(), newton_indicator, self.interactions.dirty) {
                    c.action(ColliderCtx {
                        bodies: &mut self.bodies,
                        interactions: &mut self.interactions,
                        cell: self.cell.as_ref(),
                        iter: self.iter,
                        newton_indicator,
                    })
                    .map_err(err)
                } else {
                    Ok(())
                }
            }
            Engine::InteractionLoop(il) => self.interaction_loop(il).map_err(err),
            Engine::Newton(n) => {
                self.forces.sync();
                n.step(&mut self.bodies, &self.forces, self.cell.as_mut(), self.dt)
                    .map_err(|e| self.newton_error(e))
            }
            Engine::TimeStepper(ts) => {
                if ts.is_activated(self.iter) {
                    let pwave = crate::utils::pwave_time_step(self).unwrap_or(1.0);
                    if let Some(dt) = ts.compute(&self.bodies, &self.interactions, pwave) {
                        self.dt = dt;
                    }
                }
                Ok(())
            }
            Engine::External(_) => Ok(()),
        };
        self.engines[k] = e;
        r
    }

    fn newton_error(&self, e: NewtonError) -> StepError {
        match e {
            NewtonError::NonFinite { id, what } => StepError::NonFinite {
                iter: self.iter,
                id,
                what,
                dt: self.dt,
                crit: match crate::utils::pwave_time_step(self) {
                    Some(c) => format!("PWaveTimeStep = {:e} s", c),
                    None => "unknown: no spheres".into(),
                },
            },
            NewtonError::BadMass { id } => StepError::Engine {
                iter: self.iter,
                msg: format!(
                    "body #{} is dynamic but has a non-positive mass or inertia",
                    id
                ),
            },
        }
    }

    /// `InteractionLoop::action` (core/InteractionLoop.cpp): every interaction in container order,
    /// geometry, then physics on first contact, then the law.
    fn interaction_loop(&mut self, il: &mut InteractionLoop) -> Result<(), String> {
        let ctx0 = GeomCtx {
            dt: self.dt,
            shift_vel: Vec3::zeros(),
        };
        let mut energy = LawEnergy::default();
        let n = self.interactions.list.len();
        for k in 0..n {
            let (id1_raw, id2_raw) = {
                let it = &self.interactions.list[k];
                (it.id1 as usize, it.id2 as usize)
            };
            if self.interactions.list[k].functor == GeomFunctor::Missing {
                continue;
            }
            if self.interactions.list[k].functor == GeomFunctor::Unresolved {
                let (f, swap) =
                    dispatch(il, &self.bodies.shape[id1_raw], &self.bodies.shape[id2_raw]);
                let it = &mut self.interactions.list[k];
                it.functor = f;
                if f == GeomFunctor::Missing {
                    continue;
                }
                if swap {
                    it.swap_order();
                }
            }
            let it = &mut self.interactions.list[k];
            let (id1, id2) = (it.id1 as usize, it.id2 as usize);
            let was_real = it.is_real();
            let shift2 = match &self.cell {
                Some(c) => c.shift_pos(&it.cell_dist),
                None => Vec3::zeros(),
            };
            let ctx = match &self.cell {
                Some(c) => GeomCtx {
                    shift_vel: c.shift_vel(&it.cell_dist),
                    ..ctx0
                },
                None => ctx0,
            };
            let b = &self.bodies;
            let kin = |id: usize| Kin {
                pos: b.pos[id],
                vel: b.vel[id],
                ang_vel: b.ang_vel[id],
                ori: b.ori[id],
            };
            let pr = Pair {
                s1: kin(id1),
                s2: kin(id2),
                shift2,
                is_real: was_real,
                ctx,
            };
            let g = &mut it.geom;
            let created = match (it.functor, &b.shape[id1], &b.shape[id2]) {
                (
                    GeomFunctor::SphereSphere,
                    Shape::Sphere { radius: r1 },
                    Shape::Sphere { radius: r2 },
                ) => geom::sphere_sphere::go(il.sphere_sphere.as_ref().unwrap(), *r1, *r2, &pr, g),
                (GeomFunctor::FacetSphere, Shape::Facet(f), Shape::Sphere { radius }) => {
                    geom::facet_sphere::go(il.facet_sphere.as_mut().unwrap(), f, *radius, &pr, g)
                }
                (
                    GeomFunctor::WallSphere,
                    Shape::Wall { axis, sense },
                    Shape::Sphere { radius },
                ) => geom::wall_sphere::go(
                    il.wall_sphere.as_ref().unwrap(),
                    *axis,
                    *sense,
                    *radius,
                    &pr,
                    g,
                ),
                (GeomFunctor::BoxSphere, Shape::Box { extents }, Shape::Sphere { radius }) => {
                    geom::box_sphere::go(il.box_sphere.as_ref().unwrap(), extents, *radius, &pr, g)
                }
                (f, s1, s2) => {
                    return Err(format!(
                        "internal: functor {:?} cannot handle {}+{} (#{}+#{})",
                        f,
                        s1.class_name(),
                        s2.class_name(),
                        id1,
                        id2
                    ))
                }
            };
            if !created {
                if was_real {
                    it.reset();
                }
                continue;
            }
            if it.phys.is_none() {
                if !il.frict_phys {
                    return Err(format!(
                        "Undefined IPhys dispatch for materials of #{} and #{}: add Ip2_FrictMat_FrictMat_FrictPhys()",
                        id1, id2
                    ));
                }
                let m1 = &self.materials[b.material[id1]];
                let m2 = &self.materials[b.material[id2]];
                it.phys = Some(phys::ip2_frict(m1, m2, it.geom.as_ref().unwrap()));
            }
            if !was_real {
                it.iter_made_real = self.iter;
            }
            let Some(lp) = il.cundall_strack.as_ref() else {
                return Err(format!(
                    "None of the given Law2 functors can handle interaction #{}+#{} (ScGeom, FrictPhys): add Law2_ScGeom_FrictPhys_CundallStrack()",
                    id1, id2
                ));
            };
            let lb = LawBodies {
                pos1: &b.pos[id1],
                pos2_shifted: b.pos[id2] + shift2,
            };
            let g = *it.geom.as_ref().unwrap();
            let ph = it.phys.as_mut().unwrap();
            let keep = law::go(
                lp,
                &g,
                ph,
                id1,
                id2,
                &lb,
                &mut self.forces,
                if self.track_energy {
                    Some(&mut energy)
                } else {
                    None
                },
            );
            if !keep {
                it.reset();
            }
        }
        if self.track_energy {
            self.energy.plast_dissip += energy.plast_dissip;
            self.energy.elast_potential += energy.elast_potential;
        }
        Ok(())
    }
}

/// `IGeomDispatcher::getFunctor2D`: the functor for a shape pair and whether the ids must be swapped
/// so that the facet/wall/box is body 1.
fn dispatch(il: &InteractionLoop, s1: &Shape, s2: &Shape) -> (GeomFunctor, bool) {
    use Shape::*;
    match (s1, s2) {
        (Sphere { .. }, Sphere { .. }) if il.sphere_sphere.is_some() => {
            (GeomFunctor::SphereSphere, false)
        }
        (Facet(_), Sphere { .. }) if il.facet_sphere.is_some() => (GeomFunctor::FacetSphere, false),
        (Sphere { .. }, Facet(_)) if il.facet_sphere.is_some() => (GeomFunctor::FacetSphere, true),
        (Wall { .. }, Sphere { .. }) if il.wall_sphere.is_some() => {
            (GeomFunctor::WallSphere, false)
        }
        (Sphere { .. }, Wall { .. }) if il.wall_sphere.is_some() => (GeomFunctor::WallSphere, true),
        (Box { .. }, Sphere { .. }) if il.box_sphere.is_some() => (GeomFunctor::BoxSphere, false),
        (Sphere { .. }, Box { .. }) if il.box_sphere.is_some() => (GeomFunctor::BoxSphere, true),
        _ => (GeomFunctor::Missing, false),
    }
}
