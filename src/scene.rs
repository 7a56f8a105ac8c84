//! The scene and its time step (YADE `core/Scene.cpp::moveToNextTimeStep`).
//!
//! Data flow of one step, each stage in its own module and given its state explicitly:
//! `ForceResetter` (forces) -> `collider` (bound, collider) -> `InteractionLoop` (geom -> phys ->
//! law) -> `integrator` (Newton). Engines run in list order, as in `O.engines`.

use crate::body::Bodies;
use crate::cell::Cell;
use crate::collider::{Collider, ColliderCtx};
use crate::dispatch::{self, Entry};
use crate::energy::{EnergyTracker, IdCache};
use crate::forces::Forces;
use crate::geom::{self, GeomClass, GeomCtx, Pair};
use crate::idle_skip::IdleSkip;
use crate::integrator::{Newton, NewtonError};
use crate::interaction::{GeomFunctor, Interactions};
use crate::law::{self, LawBodies, LawEnergy, LawFunctor};
use crate::material::{FrictMat, MatClass};
use crate::math::Vec3;
use crate::phys::{self, PhysClass};
use crate::shape::{Shape, ShapeClass};

/// The functor lists of an `InteractionLoop` (each functor at most once; when two geometry functors
/// claim the same shape pair, only the later one is kept, as YADE's dispatch matrix does).
#[derive(Clone, Debug, PartialEq)]
pub struct InteractionLoop {
    pub sphere_sphere: Option<geom::sphere_sphere::Params>,
    /// `Ig2_Sphere_Sphere_ScGeom6D`
    pub sphere_sphere_6d: Option<geom::grid::SixDParams>,
    pub facet_sphere: Option<geom::facet_sphere::Params>,
    pub wall_sphere: Option<geom::wall_sphere::Params>,
    pub box_sphere: Option<geom::box_sphere::Params>,
    /// `Ig2_GridNode_GridNode_GridNodeGeom6D`
    pub gridnode_gridnode: Option<geom::grid::SixDParams>,
    /// `Ig2_Sphere_GridConnection_ScGridCoGeom` (its `interactionDetectionFactor`, unused by YADE)
    pub sphere_gridco: Option<f64>,
    /// `Ig2_GridConnection_GridConnection_GridCoGridCoGeom`
    pub gridco_gridco: bool,
    /// `Ip2_FrictMat_FrictMat_FrictPhys` present.
    pub frict_phys: bool,
    /// `Ip2_CohFrictMat_CohFrictMat_CohFrictPhys` and its state.
    pub cohfrict_phys: Option<phys::CohFrictIp2>,
    /// `Ip2_ViscElMat_ViscElMat_ViscElPhys` present.
    pub viscel_phys: bool,
    /// Its MatchMakers (tc, en, et, frictAngle).
    pub viscel_ip2: phys::ViscElIp2,
    /// `Ip2_LudingMat_LudingMat_LudingPhys` present.
    pub luding_phys: bool,
    /// `Law2_ScGeom_LudingPhys_Basic` present.
    pub luding_basic: bool,
    /// `Ip2_BubbleMat_BubbleMat_BubblePhys` present.
    pub bubble_phys: bool,
    /// `Law2_ScGeom_BubblePhys_Bubble` and its state.
    pub bubble: Option<law::bubble::Params>,
    /// `Ip2_CpmMat_CpmMat_CpmPhys` and its `cohesiveThresholdIter`.
    pub cpm_phys: Option<i64>,
    /// `Ip2_FrictMat_CpmMat_FrictPhys` present.
    pub frict_cpm_phys: bool,
    /// `Law2_ScGeom_CpmPhys_Cpm` and its attributes.
    pub cpm: Option<law::cpm::Params>,
    /// `Ip2_FrictMat_FrictMat_MindlinPhys` and its attributes.
    pub mindlin_phys: Option<phys::MindlinIp2>,
    /// `Law2_ScGeom_FrictPhys_CundallStrack` and its parameters.
    pub cundall_strack: Option<law::Params>,
    /// `Law2_ScGeom6D_CohFrictPhys_CohesionMoment`
    pub cohesion_moment: Option<law::cohesion_moment::Params>,
    /// `Law2_ScGridCoGeom_FrictPhys_CundallStrack`
    pub scgridco_frict: Option<law::grid::ScGridCoParams>,
    /// `Law2_ScGridCoGeom_CohFrictPhys_CundallStrack`
    pub scgridco_cohfrict: Option<law::grid::ScGridCoParams>,
    /// `Law2_GridCoGridCoGeom_FrictPhys_CundallStrack`
    pub gridco_gridco_frict: Option<law::grid::GridCoGridCoParams>,
    /// `Law2_ScGeom_ViscElPhys_Basic` present.
    pub viscel_basic: bool,
    /// `Law2_ScGeom_MindlinPhys_Mindlin` and its attributes.
    pub mindlin: Option<law::mindlin::Params>,
    /// Each law functor's cached `O.energy` indices (`plastDissipIx`, ...), by `LawFunctor`.
    pub energy_caches: [IdCache; LawFunctor::COUNT],
    /// `InteractionLoop.callbacks`: one `SumIntrForcesCb` accumulator per callback, in list order.
    pub sum_intr_forces_cb: Vec<SumIntrForcesCb>,
    /// (ryade) Runs of steady node bonds with their rotations in lanes (`Scene::steady_bonds`),
    /// to the same bits; off only to test that.
    pub bond_lanes: bool,
}

/// `SumIntrForcesCb` (pkg/dem/UnbalancedForceCallbacks.cpp): sums |normalForce + shearForce| over the
/// real interactions (those with a non-zero force counted) during each InteractionLoop; at the start
/// of the next loop it prints the previous sums to stderr as `(force,numIntr)`, as YADE's `stepInit`
/// does with `cerr` (no newline), then resets them. It changes nothing else.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SumIntrForcesCb {
    pub force: f64,
    pub num_intr: i32,
}

impl Default for InteractionLoop {
    /// YADE's default functor lists: sphere-sphere, facet-sphere, box-sphere; FrictPhys; Cundall-Strack.
    fn default() -> Self {
        InteractionLoop {
            sphere_sphere: Some(Default::default()),
            box_sphere: Some(Default::default()),
            facet_sphere: Some(Default::default()),
            frict_phys: true,
            cundall_strack: Some(Default::default()),
            ..InteractionLoop::empty()
        }
    }
}

impl InteractionLoop {
    /// Whether this loop keeps `Scene::idle_skip` up to date (it has a functor whose potential
    /// pairs the skip covers); only such a loop may skip an idle pair.
    #[inline(always)]
    pub fn uses_idle_skip(&self) -> bool {
        self.idle_params().is_some() || self.sphere_gridco.is_some()
    }

    /// The sphere-sphere distance pre-check of the potential pairs the idle skip follows: that of
    /// `Ig2_Sphere_Sphere_ScGeom`, or, without it, that of `Ig2_Sphere_Sphere_ScGeom6D`, whose `go`
    /// starts with the ScGeom one and returns at once (no side effect) for a pair apart
    /// (pkg/dem/Ig2_Sphere_Sphere_ScGeom.cpp, Ig2_Sphere_Sphere_ScGeom6D::go).
    pub fn idle_params(&self) -> Option<&geom::sphere_sphere::Params> {
        self.sphere_sphere
            .as_ref()
            .or(self.sphere_sphere_6d.as_ref().map(|p| &p.ss))
    }

    /// The functor whose potential pairs the idle skip follows (see `idle_params`).
    fn idle_functor(&self) -> Option<GeomFunctor> {
        if self.sphere_sphere.is_some() {
            Some(GeomFunctor::SphereSphere)
        } else if self.sphere_sphere_6d.is_some() {
            Some(GeomFunctor::SphereSphere6D)
        } else {
            None
        }
    }

    /// No functor at all.
    pub fn empty() -> Self {
        InteractionLoop {
            sphere_sphere: None,
            sphere_sphere_6d: None,
            facet_sphere: None,
            wall_sphere: None,
            box_sphere: None,
            gridnode_gridnode: None,
            sphere_gridco: None,
            gridco_gridco: false,
            frict_phys: false,
            cohfrict_phys: None,
            viscel_phys: false,
            viscel_ip2: Default::default(),
            luding_phys: false,
            luding_basic: false,
            bubble_phys: false,
            bubble: None,
            cpm_phys: None,
            frict_cpm_phys: false,
            cpm: None,
            mindlin_phys: None,
            cundall_strack: None,
            cohesion_moment: None,
            scgridco_frict: None,
            scgridco_cohfrict: None,
            gridco_gridco_frict: None,
            viscel_basic: false,
            mindlin: None,
            energy_caches: Default::default(),
            sum_intr_forces_cb: Vec::new(),
            bond_lanes: true,
        }
    }

    /// The geometry functors with their declared shape classes.
    fn geom_entries(&self) -> Vec<Entry<ShapeClass, ShapeClass, GeomFunctor>> {
        use ShapeClass as S;
        let mut v = Vec::with_capacity(8);
        let mut add = |on: bool, a, b, f| {
            if on {
                v.push(Entry { a, b, f });
            }
        };
        add(
            self.sphere_sphere.is_some(),
            S::Sphere,
            S::Sphere,
            GeomFunctor::SphereSphere,
        );
        add(
            self.sphere_sphere_6d.is_some(),
            S::Sphere,
            S::Sphere,
            GeomFunctor::SphereSphere6D,
        );
        add(
            self.facet_sphere.is_some(),
            S::Facet,
            S::Sphere,
            GeomFunctor::FacetSphere,
        );
        add(
            self.wall_sphere.is_some(),
            S::Wall,
            S::Sphere,
            GeomFunctor::WallSphere,
        );
        add(
            self.box_sphere.is_some(),
            S::Box,
            S::Sphere,
            GeomFunctor::BoxSphere,
        );
        add(
            self.gridnode_gridnode.is_some(),
            S::GridNode,
            S::GridNode,
            GeomFunctor::GridNodeGridNode,
        );
        add(
            self.sphere_gridco.is_some(),
            S::Sphere,
            S::GridConnection,
            GeomFunctor::SphereGridConnection,
        );
        add(
            self.gridco_gridco,
            S::GridConnection,
            S::GridConnection,
            GeomFunctor::GridConnectionGridConnection,
        );
        v
    }

    /// The physics functor for a material pair (None: no functor can handle it), with YADE's swap
    /// of the two materials (the interaction keeps its order) when the functor was declared the other
    /// way round.
    pub(crate) fn phys_functor(
        &self,
        a: MatClass,
        b: MatClass,
    ) -> Result<Option<(PhysFunctor, bool)>, String> {
        // the common cells, answered as `resolve` would (a frictional pair one step up from a
        // cohesive material: no rival at that distance; Mindlin's Ip2 takes the FrictMat cell)
        use MatClass::{CohFrictMat as Coh, FrictMat as Fr};
        match (a, b) {
            (Fr, Fr) | (Fr, Coh) | (Coh, Fr) if self.frict_phys && self.mindlin_phys.is_none() => {
                return Ok(Some((PhysFunctor::Frict, false)))
            }
            (Coh, Coh) if self.cohfrict_phys.is_some() => {
                return Ok(Some((PhysFunctor::CohFrict, false)))
            }
            _ => {}
        }
        self.phys_functor_table(a, b)
    }

    /// `phys_functor` through the whole dispatch table.
    fn phys_functor_table(
        &self,
        a: MatClass,
        b: MatClass,
    ) -> Result<Option<(PhysFunctor, bool)>, String> {
        // registration order, on the stack (this runs for every contact every step)
        let all = [
            (self.frict_phys, MatClass::FrictMat, PhysFunctor::Frict),
            (
                self.cohfrict_phys.is_some(),
                MatClass::CohFrictMat,
                PhysFunctor::CohFrict,
            ),
            (self.viscel_phys, MatClass::ViscElMat, PhysFunctor::ViscEl),
            (self.luding_phys, MatClass::LudingMat, PhysFunctor::Luding),
            (self.bubble_phys, MatClass::BubbleMat, PhysFunctor::Bubble),
            (
                self.mindlin_phys.is_some(),
                MatClass::FrictMat,
                PhysFunctor::Mindlin,
            ),
            (self.cpm_phys.is_some(), MatClass::CpmMat, PhysFunctor::Cpm),
            (self.frict_cpm_phys, MatClass::CpmMat, PhysFunctor::FrictCpm),
        ];
        let mut buf = [Entry {
            a: MatClass::FrictMat,
            b: MatClass::FrictMat,
            f: PhysFunctor::Frict,
        }; 8];
        let mut n = 0;
        for (on, m, f) in all {
            if on {
                // Ip2_FrictMat_CpmMat_FrictPhys is declared for (FrictMat, CpmMat)
                let a = if f == PhysFunctor::FrictCpm {
                    MatClass::FrictMat
                } else {
                    m
                };
                buf[n] = Entry { a, b: m, f };
                n += 1;
            }
        }
        let v = &buf[..n];
        dispatch::resolve(v, true, a, b, Some, Some)
    }

    /// The law functor for a geometry/physics class pair.
    fn law_functor(&self, g: GeomClass, p: PhysClass) -> Result<Option<LawFunctor>, String> {
        // the common cells, answered as `resolve` would: an exact entry wins; a node bond
        // (GridNodeGeom6D, CohFrictPhys) has no entry of its own and one candidate at distance 1,
        // its parent's (ScGeom6D, CohFrictPhys)
        let exact = match (g, p) {
            (GeomClass::ScGeom, PhysClass::FrictPhys) if self.cundall_strack.is_some() => {
                Some(LawFunctor::CundallStrack)
            }
            (GeomClass::ScGeom6D | GeomClass::GridNodeGeom6D, PhysClass::CohFrictPhys)
                if self.cohesion_moment.is_some() =>
            {
                Some(LawFunctor::CohesionMoment)
            }
            (GeomClass::ScGridCoGeom, PhysClass::FrictPhys) if self.scgridco_frict.is_some() => {
                Some(LawFunctor::ScGridCoFrict)
            }
            (GeomClass::ScGridCoGeom, PhysClass::CohFrictPhys)
                if self.scgridco_cohfrict.is_some() =>
            {
                Some(LawFunctor::ScGridCoCohFrict)
            }
            (GeomClass::GridCoGridCoGeom, PhysClass::FrictPhys)
                if self.gridco_gridco_frict.is_some() =>
            {
                Some(LawFunctor::GridCoGridCoFrict)
            }
            _ => None,
        };
        if exact.is_some() {
            return Ok(exact);
        }
        self.law_functor_table(g, p)
    }

    /// `law_functor` through the whole dispatch table.
    fn law_functor_table(&self, g: GeomClass, p: PhysClass) -> Result<Option<LawFunctor>, String> {
        // registration order, on the stack (this runs for every contact every step)
        let all = [
            (
                self.cundall_strack.is_some(),
                GeomClass::ScGeom,
                PhysClass::FrictPhys,
                LawFunctor::CundallStrack,
            ),
            (
                self.cohesion_moment.is_some(),
                GeomClass::ScGeom6D,
                PhysClass::CohFrictPhys,
                LawFunctor::CohesionMoment,
            ),
            (
                self.scgridco_frict.is_some(),
                GeomClass::ScGridCoGeom,
                PhysClass::FrictPhys,
                LawFunctor::ScGridCoFrict,
            ),
            (
                self.scgridco_cohfrict.is_some(),
                GeomClass::ScGridCoGeom,
                PhysClass::CohFrictPhys,
                LawFunctor::ScGridCoCohFrict,
            ),
            (
                self.gridco_gridco_frict.is_some(),
                GeomClass::GridCoGridCoGeom,
                PhysClass::FrictPhys,
                LawFunctor::GridCoGridCoFrict,
            ),
            (
                self.viscel_basic,
                GeomClass::ScGeom,
                PhysClass::ViscElPhys,
                LawFunctor::ViscElBasic,
            ),
            (
                self.mindlin.is_some(),
                GeomClass::ScGeom,
                PhysClass::MindlinPhys,
                LawFunctor::Mindlin,
            ),
            (
                self.luding_basic,
                GeomClass::ScGeom,
                PhysClass::LudingPhys,
                LawFunctor::LudingBasic,
            ),
            (
                self.bubble.is_some(),
                GeomClass::ScGeom,
                PhysClass::BubblePhys,
                LawFunctor::Bubble,
            ),
            (
                self.cpm.is_some(),
                GeomClass::ScGeom,
                PhysClass::CpmPhys,
                LawFunctor::Cpm,
            ),
        ];
        let mut buf = [Entry {
            a: GeomClass::ScGeom,
            b: PhysClass::FrictPhys,
            f: LawFunctor::CundallStrack,
        }; 10];
        let mut n = 0;
        for (on, a, b, f) in all {
            if on {
                buf[n] = Entry { a, b, f };
                n += 1;
            }
        }
        let v = &buf[..n];
        Ok(dispatch::resolve(v, false, g, p, |_| None, |_| None)?.map(|(f, _)| f))
    }
}

/// Which Ip2 functor builds an interaction's physics.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PhysFunctor {
    Frict,
    CohFrict,
    ViscEl,
    Mindlin,
    Luding,
    /// `Ip2_CpmMat_CpmMat_CpmPhys`
    Cpm,
    /// `Ip2_FrictMat_CpmMat_FrictPhys`
    FrictCpm,
    Bubble,
}

#[derive(Clone, Debug)]
pub enum Engine {
    ForceResetter,
    /// A standalone `BoundDispatcher` (bounds without a collider).
    Bounds(Box<crate::bound::BoundFunctors>),
    Collider(Box<Collider>),
    InteractionLoop(Box<InteractionLoop>),
    Newton(Box<Newton>),
    TimeStepper(Box<crate::timestepper::GlobalStiffnessTimeStepper>),
    Translation(Box<crate::kinematic::TranslationEngine>),
    Rotation(Box<crate::kinematic::RotationEngine>),
    ServoPid(Box<crate::kinematic::ServoPid>),
    Helix(Box<crate::kinematic::HelixEngine>),
    CombinedKinematic(Box<crate::kinematic::CombinedKinematicEngine>),
    /// A kinematic engine without a variant of its own (InterpolatingHelixEngine, BicyclePedalEngine).
    Kinematic(Box<crate::kinematic::KinematicPart>),
    DirectedForce(Box<crate::force_engine::InterpolatingDirectedForceEngine>),
    Force(Box<crate::force_engine::ForceEngine>),
    HarmonicForce(Box<crate::force_engine::HarmonicForceEngine>),
    TriaxialStress(Box<crate::triax::TriaxialStressController>),
    /// The study's piston law (`RyadePistonController`, a ryade extension: not a YADE class).
    Piston(Box<crate::piston::PistonController>),
    PeriTriax(Box<crate::peri_triax::PeriTriax>),
    Hydro(Box<crate::hydro::HydroForceEngine>),
    /// An engine run outside the core (e.g. a Python `PyRunner`): the step calls the hook given to
    /// `Scene::step_with` with this id, at this position in the engine list.
    External(u32),
}

impl Engine {
    pub fn class_name(&self) -> &'static str {
        match self {
            Engine::ForceResetter => "ForceResetter",
            Engine::Bounds(_) => "BoundDispatcher",
            Engine::Collider(_) => "InsertionSortCollider",
            Engine::InteractionLoop(_) => "InteractionLoop",
            Engine::Newton(_) => "NewtonIntegrator",
            Engine::TimeStepper(_) => "GlobalStiffnessTimeStepper",
            Engine::Translation(_) => "TranslationEngine",
            Engine::Rotation(_) => "RotationEngine",
            Engine::ServoPid(_) => "ServoPIDController",
            Engine::Helix(_) => "HelixEngine",
            Engine::CombinedKinematic(_) => "CombinedKinematicEngine",
            Engine::Kinematic(k) => k.class_name(),
            Engine::DirectedForce(_) => "InterpolatingDirectedForceEngine",
            Engine::Force(_) => "ForceEngine",
            Engine::HarmonicForce(_) => "HarmonicForceEngine",
            Engine::TriaxialStress(t) => t.class_name(),
            Engine::Piston(_) => "RyadePistonController",
            Engine::PeriTriax(_) => "PeriTriaxController",
            Engine::Hydro(_) => "HydroForceEngine",
            Engine::External(_) => "External",
        }
    }
}

/// Why a step stopped. Carries what a user needs to fix it.
#[derive(Debug, Clone, thiserror::Error)]
pub enum StepError {
    /// A body's motion came out non-finite; `report` says what was found (see `non_finite_report`).
    #[error("step {iter}: {report}")]
    NonFinite {
        iter: i64,
        id: usize,
        report: String,
    },
    #[error("step {iter}: {msg}")]
    Engine { iter: i64, msg: String },
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
    /// `O.energy` (filled while `track_energy`)
    pub energy: EnergyTracker,
    /// Threads of the YADE-order path (1: none). The steady sphere-sphere contacts are evaluated in
    /// parallel and their forces added in container order afterwards, so every thread count gives
    /// YADE's single-thread bits.
    pub threads: usize,
    /// The threaded pre-pass and Newton's parallel orientation pass run only on containers of at
    /// least this many slots (default `PAR_MIN_SLOTS`); below it the pool wake-ups cost more than
    /// the parallel parts save, so the serial code runs (the same bits either way).
    pub par_min_slots: usize,
    pub pool: Pool,
    /// Lets the interaction loop skip the distance checks of idle pairs that provably stay apart
    /// (same decisions, see `idle_skip`).
    pub idle_skip: IdleSkip,
    /// `O.timingEnabled`: `run_engine` then adds each engine's wall time and run count to `timing`.
    pub timing_enabled: bool,
    /// Per engine slot (grown on demand; `Engine::External` slots are timed by their runner).
    pub timing: Vec<crate::timing::EngineTiming>,
    /// Set by an engine that ends the run after this step (`RyadePistonController`, as a `PyRunner`'s
    /// `O.stopAtIter = O.iter + 1`); the run loop (compat's `run_steps`, `O.run`) stops after the
    /// step and clears it.
    pub stop_requested: bool,
    /// Engine slot whose PeriTriaxController asked for its (Python) doneHook during the current
    /// step; the runner of `step_with` takes it (`DONE_HOOK | slot`).
    pub done_hook_pending: Option<usize>,
    /// (ryade) How many runs of node bonds the walk took with their rotations in lanes
    /// (`Scene::steady_bonds`).
    pub bond_lane_runs: u64,
}

/// Bit set in the id `Scene::step_with` passes to its hook for a pending doneHook (the rest of the
/// id is the engine slot).
pub const DONE_HOOK: u32 = 1 << 31;

/// Default `Scene::par_min_slots`. Measured with 2 threads against 1 (2-core VM, session 5): the
/// study's r05 G medium (~5,700 slots) 0.93x and r03 N small (~12,700 slots) 0.98x with the
/// pre-pass, the 8,000-sphere bench scene (77,800 slots) 1.40x.
pub const PAR_MIN_SLOTS: usize = 16384;

/// The thread pool of the YADE-order path, built on first use for `Scene::threads`.
#[derive(Clone, Debug, Default)]
pub struct Pool(Option<std::sync::Arc<rayon::ThreadPool>>);

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
            energy: EnergyTracker::default(),
            threads: 1,
            par_min_slots: PAR_MIN_SLOTS,
            pool: Pool::default(),
            idle_skip: IdleSkip::default(),
            timing_enabled: false,
            timing: Vec::new(),
            stop_requested: false,
            done_hook_pending: None,
            bond_lane_runs: 0,
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
    /// `External` engines, or a PeriTriaxController whose doneHook has no recorded effect, must be
    /// stepped with `step_with`.
    pub fn step(&mut self) -> Result<(), StepError> {
        self.step_with(&mut |id, s: &mut Scene| {
            if id & DONE_HOOK != 0 {
                let k = (id & !DONE_HOOK) as usize;
                let hook = match s.engines.get(k) {
                    Some(Engine::PeriTriax(p)) => p.done_hook.clone(),
                    Some(Engine::TriaxialStress(_)) => {
                        return Err(format!(
                            "TriaxialCompressionEngine writes its snapshot files at iteration {}: that needs `compat run` (or noFiles=True)",
                            s.iter
                        ))
                    }
                    _ => String::new(),
                };
                return Err(format!(
                    "PeriTriaxController.doneHook '{}' fired at iteration {}: a Python hook needs `compat run` (or its recorded effect in the scene file)",
                    hook, s.iter
                ));
            }
            Err(format!(
                "external engine {} has no runner (at iteration {})",
                id, s.iter
            ))
        })
    }

    /// One step; `hook(id, scene)` runs each `Engine::External(id)` with full access to the scene,
    /// and each pending doneHook (`DONE_HOOK | slot`) right after its controller.
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
                    if let Some(slot) = self.done_hook_pending.take() {
                        let iter = self.iter;
                        hook(DONE_HOOK | slot as u32, self)
                            .map_err(|msg| StepError::Engine { iter, msg })?;
                    }
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
        let t0 = self.timing_enabled.then(std::time::Instant::now);
        let iter = self.iter;
        let err = |msg: String| StepError::Engine { iter, msg };
        let newton_indicator = self.newton().map(|n| n.max_velocity_sq);
        let mut e = std::mem::replace(&mut self.engines[k], Engine::External(u32::MAX));
        // whether the engine counts as run (YADE's `isActivated`)
        let mut activated = true;
        // NewtonIntegrator's checkpoint times while timing (`timing::NEWTON_CHECKPOINTS`)
        let mut newton_marks: crate::timing::Marks = Default::default();
        let r = match &mut e {
            Engine::ForceResetter => {
                self.forces.reset(self.bodies.len(), self.iter);
                if self.track_energy {
                    self.energy.reset_resettables();
                }
                Ok(())
            }
            // BoundDispatcher::action on its own: YADE's defaults sweepDist=0, targetInterv=-1 give
            // plain boxes (the sweep is the collider's business)
            Engine::Bounds(f) => crate::bound::update_bounds(
                f,
                &mut self.bodies,
                self.cell.as_ref(),
                self.iter,
                &crate::bound::Sweep {
                    sweep_dist: 0.0,
                    min_sweep_dist_factor: 0.2,
                    target_interv: -1,
                },
            )
            .map_err(err),
            Engine::Collider(c) => {
                activated =
                    c.is_activated(self.bodies.len(), newton_indicator, self.interactions.dirty);
                if activated {
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
                if t0.is_some() {
                    newton_marks[0] = Some(std::time::Instant::now());
                }
                self.forces.sync();
                if t0.is_some() {
                    newton_marks[1] = Some(std::time::Instant::now());
                }
                // the orientation pass goes parallel on the scenes large enough for the pre-pass
                // (on smaller ones one pool wake-up costs more than it saves)
                let pool = if self.interactions.list.len() >= self.par_min_slots {
                    self.pool_for_threads()
                } else {
                    None
                };
                let r = n.step(
                    &mut self.bodies,
                    &mut self.forces,
                    self.cell.as_mut(),
                    self.dt,
                    pool.as_deref(),
                    self.track_energy.then_some(&mut self.energy),
                );
                if t0.is_some() {
                    newton_marks[2] = Some(std::time::Instant::now());
                    newton_marks[3] = newton_marks[2];
                }
                r.map_err(|e| self.newton_error(e))
            }
            Engine::TimeStepper(ts) => {
                activated = ts.is_activated(self.iter);
                if activated {
                    let pwave = crate::utils::pwave_time_step(self).unwrap_or(1.0);
                    if let Some(dt) = ts.compute(&self.bodies, &self.interactions, pwave) {
                        self.dt = dt;
                    }
                }
                Ok(())
            }
            Engine::Translation(t) => {
                t.action(&mut self.bodies);
                Ok(())
            }
            Engine::Rotation(r) => {
                r.action(&mut self.bodies, self.dt);
                Ok(())
            }
            Engine::ServoPid(s) => {
                s.action(&mut self.bodies, &self.forces, self.iter);
                Ok(())
            }
            Engine::Helix(h) => {
                h.action(&mut self.bodies, self.dt);
                Ok(())
            }
            Engine::CombinedKinematic(c) => c
                .action(
                    &mut self.bodies,
                    &self.forces,
                    self.dt,
                    self.iter,
                    self.time,
                )
                .map(|_| ())
                .map_err(err),
            Engine::Kinematic(c) => c
                .action(
                    &mut self.bodies,
                    &self.forces,
                    self.dt,
                    self.iter,
                    self.time,
                )
                .map_err(err),
            Engine::DirectedForce(f) => f
                .action(&mut self.forces, self.bodies.len(), self.time)
                .map_err(err),
            Engine::Force(f) => {
                f.action(&mut self.forces, self.bodies.len());
                Ok(())
            }
            Engine::HarmonicForce(h) => {
                h.action(&mut self.forces, self.bodies.len(), self.time);
                Ok(())
            }
            Engine::Hydro(h) => h.action(&self.bodies, &mut self.forces).map_err(err),
            Engine::TriaxialStress(t) => {
                let r = t.action(self).map_err(err);
                // a TriaxialCompressionEngine's snapshot files: written by the runner (Python) right
                // after the engine, as a doneHook is
                if t.compression
                    .as_ref()
                    .is_some_and(|c| !c.pending_files.is_empty())
                {
                    self.done_hook_pending = Some(k);
                }
                r
            }
            Engine::Piston(pc) => {
                activated = pc.periodic.is_activated(self.iter);
                if activated {
                    let mut io = crate::piston::SceneIo {
                        bodies: &mut self.bodies,
                        forces: &self.forces,
                    };
                    match pc.action(&mut io, self.iter) {
                        Ok(stop) => {
                            self.stop_requested |= stop;
                            Ok(())
                        }
                        Err(m) => Err(err(m)),
                    }
                } else {
                    Ok(())
                }
            }
            Engine::PeriTriax(p) => match p.action(self) {
                // recorded effects (scene files) are applied here; a Python hook runs after the
                // engine (`step_with`), before the next one, as YADE runs it inside `action`
                Ok(true) if p.replay_hooks => match p.replay_hook(self.iter) {
                    Ok(dead) => {
                        if dead {
                            self.engine_dead.resize(self.engines.len(), false);
                            self.engine_dead[k] = true;
                        }
                        Ok(())
                    }
                    Err(e) => Err(err(e)),
                },
                Ok(true) => {
                    self.done_hook_pending = Some(k);
                    Ok(())
                }
                Ok(false) => Ok(()),
                Err(e) => Err(err(e)),
            },
            Engine::External(_) => {
                activated = false;
                Ok(())
            }
        };
        self.engines[k] = e;
        if let (Some(t0), true) = (t0, activated) {
            let n = self.engines.len();
            crate::timing::record(&mut self.timing, k, n, t0, &newton_marks);
        }
        r
    }

    fn newton_error(&self, e: NewtonError) -> StepError {
        match e {
            NewtonError::NonFinite { id, .. } => StepError::NonFinite {
                iter: self.iter,
                id,
                report: self.non_finite_report(id),
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

    /// What a user needs when body `id` came out of NewtonIntegrator non-finite: the quantity found
    /// non-finite and its value, the body's mass, O.dt against the critical time step, its contacts
    /// now, and the cause those facts point to (not always the time step).
    pub fn non_finite_report(&self, id: usize) -> String {
        let b = &self.bodies;
        let fin = |v: &Vec3| v.iter().all(|x| x.is_finite());
        let fmt = |v: &Vec3| format!("({:e}, {:e}, {:e})", v[0], v[1], v[2]);
        let (f, m) = (*self.forces.force(id), *self.forces.torque(id));
        let mass = b.mass[id];
        let shape = match b.shape[id].sphere_radius() {
            Some(r) => format!("{} of radius {:e} m", b.shape[id].class_name(), r),
            None => b.shape[id].class_name().to_string(),
        };
        let mut s = format!("body #{} ({}, mass {:e} kg): ", id, shape, mass);
        let quantity = if !fin(&f) {
            format!("its force {} N is not finite", fmt(&f))
        } else if !fin(&m) {
            format!("its torque {} N m is not finite", fmt(&m))
        } else if !fin(&b.vel[id]) {
            format!(
                "its velocity {} m/s came out not finite (force {} N)",
                fmt(&b.vel[id]),
                fmt(&f)
            )
        } else {
            format!(
                "its position {} m came out not finite (velocity {} m/s)",
                fmt(&b.pos[id]),
                fmt(&b.vel[id])
            )
        };
        s += &quantity;
        let crit = crate::utils::pwave_time_step(self);
        s += &match crit {
            Some(c) => format!(
                ". O.dt = {:e} s is {:.3} x the critical time step (PWaveTimeStep = {:e} s)",
                self.dt,
                self.dt / c,
                c
            ),
            None => format!(
                ". O.dt = {:e} s (no sphere, so no PWaveTimeStep to compare with)",
                self.dt
            ),
        };
        // its contacts now, deepest first
        struct Contact {
            pen: f64,
            text: String,
            other: u32,
            force_finite: bool,
            other_finite: bool,
            kn_finite: bool,
        }
        let state_finite = |j: usize| fin(&b.pos[j]) && fin(&b.vel[j]) && fin(&b.ang_vel[j]);
        let mut contacts: Vec<Contact> = Vec::new();
        for it in &self.interactions.list {
            if !it.is_real() || (it.id1 as usize != id && it.id2 as usize != id) {
                continue;
            }
            let other = if it.id1 as usize == id {
                it.id2
            } else {
                it.id1
            };
            let (g, p) = (it.geom.as_ref().unwrap(), it.phys.as_ref().unwrap());
            let other_finite = state_finite(other as usize);
            contacts.push(Contact {
                pen: if g.pen.is_nan() { f64::INFINITY } else { g.pen },
                text: format!(
                    "#{} ({}{}, penetration {:e} m, kn {:e} N/m, normal force {:e} N)",
                    other,
                    b.shape[other as usize].class_name(),
                    if other_finite {
                        ""
                    } else {
                        " whose state is not finite"
                    },
                    g.pen,
                    p.kn,
                    crate::math::norm(&p.normal_force)
                ),
                other,
                force_finite: fin(&p.normal_force) && fin(&p.shear_force),
                other_finite,
                kn_finite: p.kn.is_finite() && p.ks.is_finite(),
            });
        }
        contacts.sort_by(|a, b| b.pen.total_cmp(&a.pen));
        s += &if contacts.is_empty() {
            ". It has no contact now".to_string()
        } else {
            format!(
                ". Its contacts now ({}): {}",
                contacts.len(),
                contacts
                    .iter()
                    .take(3)
                    .map(|c| c.text.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        };
        // the cause the facts point to
        let above = crit.is_some_and(|c| self.dt > c);
        let dynamic = b.blocked[id] != crate::body::DOF_ALL;
        let cause = if above {
            "the time step is above the critical one: lower O.dt (e.g. O.dt = 0.5*PWaveTimeStep())"
                .to_string()
        } else if dynamic && !(mass.is_finite() && mass > 0.0) {
            "the body is dynamic but its mass is not a positive number: check its material density and size".to_string()
        } else if !fin(&f) {
            // a contact partner finite now was finite before the step (Newton stops at the first
            // failing body, and a non-finite state stays non-finite): then the non-finite input of
            // the contact was this body's own state
            match contacts.iter().find(|c| !c.force_finite) {
                Some(c) if !c.kn_finite => format!(
                    "the contact with #{} has a non-finite stiffness: check both materials (young, poisson) and sizes",
                    c.other
                ),
                Some(c) if !c.other_finite => format!(
                    "the contact with #{}, whose own state is not finite, gives a non-finite force",
                    c.other
                ),
                Some(c) => format!(
                    "its own position or velocity was already not finite before step {} (its contact with #{} turned it into a non-finite force): set so by the script (a NaN or inf given to the body) or by an engine",
                    self.iter, c.other
                ),
                None => "no contact of this body has a non-finite force: it comes from a force the script or an engine added (O.forces.addF/setPermF) or from gravity".to_string(),
            }
        } else if !fin(&m) {
            "no contact is the likely source: check the torques the script or an engine added (O.forces.addT/setPermT)".to_string()
        } else {
            // force, mass and dt are finite: v + dt*a and x + dt*v can only be non-finite if v or x were
            format!(
                "its state was already not finite (or astronomically large) before step {}: set so by the script (a NaN or inf given to the body) or by an engine; the time step is below the critical one",
                self.iter
            )
        };
        s += &format!(". Likely cause: {}", cause);
        s
    }

    /// `utils.createInteraction(id1, id2)` (`InteractionLoop::createExplicitInteraction`,
    /// core/InteractionLoop.cpp, with `IGeomDispatcher::explicitAction`): the geometry is forced with
    /// the first InteractionLoop's functors, the physics created, `iterMadeReal = iter`, and the
    /// interaction appended to the container. In a periodic scene the period is the nearest image
    /// `-(int)((x2-x1)/size + 0.5)` per axis. Returns the interaction's index.
    pub fn create_interaction(&mut self, id1: usize, id2: usize) -> Result<usize, String> {
        let n = self.bodies.len();
        if id1 >= n || id2 >= n {
            return Err(format!("No body #{}", if id1 >= n { id1 } else { id2 }));
        }
        if let Some(k) = self.interactions.find(id1 as u32, id2 as u32) {
            if self.interactions.list[k].is_real() {
                return Err(format!("Interaction #{}+#{} already exists.", id1, id2));
            }
            self.interactions.erase_at(k);
        }
        let Some(ke) = self
            .engines
            .iter()
            .position(|e| matches!(e, Engine::InteractionLoop(_)))
        else {
            return Err("No IGeomDispatcher in engines or inside InteractionLoop.".into());
        };
        let mut cell_dist = [0i32; 3];
        if let Some(c) = &self.cell {
            let size = c.size();
            for (i, cd) in cell_dist.iter_mut().enumerate() {
                // a C++ cast to int truncates toward zero
                *cd =
                    -(((self.bodies.pos[id2][i] - self.bodies.pos[id1][i]) / size[i] + 0.5) as i32);
            }
        }
        let mut e = std::mem::replace(&mut self.engines[ke], Engine::External(u32::MAX));
        let Engine::InteractionLoop(il) = &mut e else {
            unreachable!()
        };
        let r = self.create_interaction_with(il, id1, id2, cell_dist);
        self.engines[ke] = e;
        r
    }

    fn create_interaction_with(
        &mut self,
        il: &mut InteractionLoop,
        id1: usize,
        id2: usize,
        cell_dist: [i32; 3],
    ) -> Result<usize, String> {
        let (s1, s2) = (&self.bodies.shape[id1], &self.bodies.shape[id2]);
        let found =
            dispatch::resolve(&il.geom_entries(), true, s1.class(), s2.class(), Some, Some)?;
        let Some((functor, swap)) = found else {
            return Err(format!(
                "IGeomDispatcher::explicitAction could not dispatch for given types ({},{}).",
                s1.class_name(),
                s2.class_name()
            ));
        };
        let mut it =
            crate::interaction::Interaction::new(id1 as u32, id2 as u32, cell_dist, self.iter);
        it.functor = functor;
        if swap {
            it.swap_order();
        }
        let (a, b) = (it.id1 as usize, it.id2 as usize);
        self.interactions.insert(it);
        let k = self.interactions.find(a as u32, b as u32).unwrap();
        // YADE computes shift2 from the period before a functor swap negates it (kept)
        let shift2 = match &self.cell {
            Some(c) => c.shift_pos(&cell_dist),
            None => Vec3::zeros(),
        };
        let ctx = GeomCtx {
            dt: self.dt,
            shift_vel: match &self.cell {
                Some(c) => c.shift_vel(&cell_dist_of(&self.interactions, k)),
                None => Vec3::zeros(),
            },
        };
        // `force = true`: the functors skip their distance checks exactly as for a real interaction
        let created = self.geometry(il, k, functor, a, b, true, &shift2, &ctx)?;
        if !created {
            self.interactions.erase_at(k);
            return Err(format!(
                "Functor {:?} returned false, even if asked to force IGeom creation.",
                functor
            ));
        }
        self.physics(il, k, a, b)?;
        self.interactions.list[k].iter_made_real = self.iter;
        // a contact made outside the loop may be taken over by a neighbouring connection pair
        if self.touches_conn(functor, a, b) {
            self.idle_skip.gained_grid_real(a as u32, b as u32);
        }
        Ok(k)
    }

    /// `InteractionLoop::action` (core/InteractionLoop.cpp): every interaction in container order:
    /// geometry, physics (created on first contact; the cohesive Ip2 also runs on existing physics),
    /// then the law.
    pub(crate) fn interaction_loop(&mut self, il: &mut InteractionLoop) -> Result<(), String> {
        for cb in il.sum_intr_forces_cb.iter_mut() {
            eprint!(
                "({},{})",
                crate::utils::cxx_stream_double(cb.force),
                cb.num_intr
            );
            *cb = SumIntrForcesCb::default();
        }
        // the laws add to O.energy as they go (YADE's scene->energy->add per contact); the tracker
        // and the functors' index caches are moved out for the loop and put back after it
        let mut tracker = std::mem::take(&mut self.energy);
        let mut caches = std::mem::take(&mut il.energy_caches);
        let mut energy = LawEnergy {
            tracker: &mut tracker,
            caches: &mut caches,
            functor: LawFunctor::CundallStrack,
            trace: false,
        };
        let r = self.interaction_loop_with(il, &mut energy);
        // (after an error too: the partners noted for this walk hold for it alone)
        self.idle_skip.end_walk();
        self.energy = tracker;
        il.energy_caches = caches;
        if !il.sum_intr_forces_cb.is_empty() {
            // YADE calls the callback right after each interaction's law; nothing later in the loop
            // touches an interaction's forces, so one pass in container order afterwards sums the
            // same values in the same order
            for it in self.interactions.list.iter().filter(|it| it.is_real()) {
                let Some(ph) = it.phys.as_ref() else { continue };
                let f = ph.normal_force + ph.shear_force;
                if f == Vec3::zeros() {
                    continue;
                }
                let n = crate::math::norm(&f);
                for cb in il.sum_intr_forces_cb.iter_mut() {
                    cb.num_intr += 1;
                    cb.force += n;
                }
            }
        }
        r
    }

    fn interaction_loop_with(
        &mut self,
        il: &mut InteractionLoop,
        energy: &mut LawEnergy<'_>,
    ) -> Result<(), String> {
        let ctx0 = GeomCtx {
            dt: self.dt,
            shift_vel: Vec3::zeros(),
        };
        let mut geom_entries = None;
        if il.uses_idle_skip() {
            self.idle_skip.prepare(
                &self.bodies,
                self.cell.as_ref(),
                il.idle_params()
                    .map_or(1.0, |p| p.interaction_detection_factor),
                &mut self.interactions.scan,
            );
        }
        if let Some(runs) = self.pre_pass(il)? {
            for ev in runs.iter().flatten() {
                self.event(il, *ev, &ctx0, energy, &mut geom_entries)?;
            }
        } else if let Some(cfg) = self.pre_cfg(il, true)? {
            // one thread: steady contacts and idle pairs by `pre_slot`, as the threaded pre-pass
            // does (leaner than the general visit: ~3 % on scene (a)), other slots visited
            let n = self.interactions.list.len();
            let skip_gc = il.uses_idle_skip();
            let mut k = 0;
            while k < n {
                // an idle sphere-connection pair still apart by the bound: what `visit` would
                // decide first, without the walk's event
                let sc = &self.interactions.scan[k];
                if sc.idle_gc && skip_gc && self.idle_skip.skips_gridco(sc) {
                    k += 1;
                    continue;
                }
                #[cfg(target_arch = "x86_64")]
                if cfg.bond_lanes {
                    let (b, skip) = (&self.bodies, &self.idle_skip);
                    let (scan, list) = (&self.interactions.scan, &self.interactions.list);
                    let bond = |j: usize| steady_bond_radii(&cfg, b, skip, &scan[j], &list[j]);
                    if let Some(r) = bond(k) {
                        // (a run of three or four in a row)
                        let mut run = [(k, r); 4];
                        let mut m = 1;
                        while m < 4 && k + m < n {
                            let Some(r) = bond(k + m) else { break };
                            run[m] = (k + m, r);
                            m += 1;
                        }
                        if m >= 3 {
                            self.steady_bonds(&cfg, &run[..m]);
                            k += m;
                            continue;
                        }
                    }
                }
                const AHEAD: usize = 24;
                if k + AHEAD < n && !self.interactions.scan[k + AHEAD].is_idle() {
                    self.interactions.prefetch(k + AHEAD);
                }
                if k + EXT_AHEAD < n && !self.interactions.scan[k + EXT_AHEAD].is_idle() {
                    self.interactions.prefetch_ext(k + EXT_AHEAD);
                }
                let ev = pre_slot(
                    &cfg,
                    &self.bodies,
                    self.cell.as_ref(),
                    &self.idle_skip,
                    k as u32,
                    &mut self.interactions.scan[k],
                    &mut self.interactions.list[k],
                );
                // (a reset pair's functor resolved first, as `visit` would, for the lean paths)
                let lean = |s: &mut Self, ge: &mut Option<_>| -> Result<bool, String> {
                    let sc = &s.interactions.scan[k];
                    if !(sc.idle || sc.idle_gc) {
                        s.resolve_functor(il, k, ge)?;
                    }
                    Ok(s.steady_gridco(&cfg, k) || s.apart_gridco(&cfg, k))
                };
                match ev {
                    Some(Event::Visit(_)) if lean(self, &mut geom_entries)? => {}
                    Some(ev) => self.event(il, ev, &ctx0, energy, &mut geom_entries)?,
                    None => {}
                }
                k += 1;
            }
        } else {
            let n = self.interactions.list.len();
            for k in 0..n {
                const AHEAD: usize = 24;
                if k + AHEAD < n && !self.interactions.scan[k + AHEAD].is_idle() {
                    self.interactions.prefetch(k + AHEAD);
                }
                if k + EXT_AHEAD < n && !self.interactions.scan[k + EXT_AHEAD].is_idle() {
                    self.interactions.prefetch_ext(k + EXT_AHEAD);
                }
                self.visit(il, k, &ctx0, energy, &mut geom_entries)?;
            }
        }
        Ok(())
    }

    /// Slots `ks` (three or four in a row, each a steady node bond: `steady_bond_radii`) as
    /// `pre_slot` and their events do them one by one, but with the rotations of the bonds that
    /// were real in lanes (`fast::rotations_lanes`: the f64 path's bits): each bond's geometry,
    /// then the rotations, then each one's law and event. A bond reads only its nodes and its own
    /// state, which no other bond's work changes (the connection body moves with the event), so
    /// the bits are those of the one-by-one walk.
    #[cfg(target_arch = "x86_64")]
    fn steady_bonds(&mut self, cfg: &PreCfg, ks: &[(usize, (f64, f64))]) {
        let (p6, cm) = cfg.grid_6d.expect("steady bonds need grid_6d");
        let cell = self.cell.as_ref();
        self.bond_lane_runs += 1;
        let list = &mut self.interactions.list;
        // per bond: whether it is new, the connection body's move, body 2's shift (None: the
        // geometry erases it)
        let mut made = [None; 4];
        for (q, &(k, (r1, r2))) in ks.iter().enumerate() {
            let it = &mut list[k];
            let (id1, id2) = (it.id1 as usize, it.id2 as usize);
            let (shift2, ctx) = cfg.shifts(cell, &it.cell_dist);
            let pr = Pair::of(&self.bodies, id1, id2, shift2, true, ctx);
            let mut conn_sync = None;
            let (g, e) = (&mut it.geom, &mut it.ext);
            made[q] = geom::grid::six_d_geometry(&p6, r1, r2, &pr, g, e, true, &mut conn_sync)
                .map(|is_new| (is_new, conn_sync, shift2));
        }
        fn rot_of<'a>(
            b: &'a Bodies,
            it: &'a crate::interaction::Interaction,
        ) -> crate::fast::RotOf<'a> {
            crate::fast::RotOf {
                ori1: &b.ori[it.id1 as usize],
                ori2: &b.ori[it.id2 as usize],
                rot: it
                    .geom_ext()
                    .and_then(|g| g.rot())
                    .expect("a bond's rotations"),
                normal: &it.geom.as_ref().expect("a bond's geometry").normal,
            }
        }
        let was_real = |q: usize| matches!(made[q], Some((false, ..)));
        let b = &self.bodies;
        let tb = if (0..ks.len()).all(was_real) {
            let of: [_; 4] = std::array::from_fn(|l| rot_of(b, &list[ks[l.min(ks.len() - 1)].0]));
            // SAFETY: AVX2 (`PreCfg::bond_lanes`)
            unsafe { crate::fast::rotations_lanes(&of, p6.creep) }
        } else {
            None
        };
        for (q, &(k, _)) in ks.iter().enumerate() {
            let Some((is_new, conn_sync, shift2)) = made[q] else {
                list[k].reset();
                continue;
            };
            let it = &mut list[k];
            let (id1, id2) = (it.id1 as usize, it.id2 as usize);
            let normal = it.geom.as_ref().expect("a bond's geometry").normal;
            let rot = it
                .ext
                .as_mut()
                .and_then(|e| e.geom.as_mut())
                .and_then(|g| g.rot_mut());
            let rot = rot.expect("a bond's rotations");
            match tb {
                Some(tb) => (rot.twist, rot.bending) = tb[q],
                // (`six_d_rotations`, on with `bond_lanes`)
                None => {
                    let (o1, o2) = (&self.bodies.ori[id1], &self.bodies.ori[id2]);
                    rot.precompute_rotations(o1, o2, &normal, is_new, p6.creep)
                }
            }
            match steady_six_d_law(&cm, cfg, &self.bodies, (id1, id2), shift2, it, conn_sync) {
                Some((l, cs)) => apply_bond(&mut self.bodies, &mut self.forces, (id1, id2), &l, cs),
                None => it.reset(),
            }
        }
    }

    /// Slot `k` when it is a real sphere-connection contact whose geometry reduces to its own
    /// (`geom::grid::sphere_gridco_steady`, with the sphere's grid partners noted for this walk)
    /// and whose physics is a FrictPhys left alone by its Ip2: the geometry, then
    /// Law2_ScGridCoGeom_FrictPhys_CundallStrack, as `visit` would do them (no share to sync, no
    /// contact made). False, with nothing done, when that does not hold.
    #[inline(always)]
    fn steady_gridco(&mut self, cfg: &PreCfg, k: usize) -> bool {
        let Some(gc) = cfg.gridco.as_ref() else {
            return false;
        };
        let it = &mut self.interactions.list[k];
        if it.functor != GeomFunctor::SphereGridConnection || !it.is_real() {
            return false;
        }
        let b = &self.bodies;
        let (id1, id2) = (it.id1 as usize, it.id2 as usize);
        let nm = self.materials.len();
        if !gc.frict[b.material[id1] * nm + b.material[id2]]
            || it.phys_class() != PhysClass::FrictPhys
        {
            return false;
        }
        let Some(partners) = self.idle_skip.grid_partners(it.id1) else {
            return false;
        };
        let (shift2, ctx) = cfg.shifts(self.cell.as_ref(), &it.cell_dist);
        let cell = self.cell.as_ref();
        if !geom::grid::sphere_gridco_steady(it, b, cell, &ctx, &shift2, partners) {
            return false;
        }
        let (Some(g), Some(ph), Some(geom::GeomExt::ScGridCo(x))) = (
            it.geom.as_ref(),
            it.phys.as_mut(),
            it.ext.as_ref().and_then(|e| e.geom.as_ref()),
        ) else {
            unreachable!("a real sphere-connection contact has its ScGridCoGeom")
        };
        if !law::grid::scgridco_frict(&gc.p, g, x, ph, id1, id2, &mut self.forces, None) {
            it.reset();
        }
        true
    }

    /// Whether a law may add to `O.energy` this step: `O.trackEnergy`, or a GridCoGridCo law with
    /// `traceEnergy` (which YADE's law adds `elastPotential` for even without trackEnergy).
    fn energy_wanted(&self, il: &InteractionLoop) -> bool {
        self.track_energy || il.gridco_gridco_frict.is_some_and(|p| p.trace_energy)
    }

    /// What `pre_slot` left for the container-order walk: visit the slot, add the steady
    /// contact's load, or erase it.
    #[inline(always)]
    fn event(
        &mut self,
        il: &mut InteractionLoop,
        ev: Event,
        ctx0: &GeomCtx,
        energy: &mut LawEnergy<'_>,
        geom_entries: &mut Option<Vec<Entry<ShapeClass, ShapeClass, GeomFunctor>>>,
    ) -> Result<(), String> {
        match ev {
            Event::Visit(k) => self.visit(il, k as usize, ctx0, energy, geom_entries)?,
            Event::Load(id1, id2, l) => {
                law::apply(&mut self.forces, id1 as usize, id2 as usize, &l)
            }
            Event::CohLoad(id1, id2, l) => {
                law::cohesion_moment::apply(&mut self.forces, id1 as usize, id2 as usize, &l)
            }
            Event::BondLoad(id1, id2, l, conn_sync) => {
                let ids = (id1 as usize, id2 as usize);
                apply_bond(&mut self.bodies, &mut self.forces, ids, &l, conn_sync)
            }
            Event::Erase(k) => self.interactions.list[k as usize].reset(),
        }
        Ok(())
    }

    /// The geometry functor of slot `k` when not yet resolved (a new or reset interaction): YADE's
    /// dispatch on the two shapes' classes (`Missing` when none fits), the bodies swapped when the
    /// functor takes them the other way round. The entries are listed once per walk.
    #[inline(always)]
    fn resolve_functor(
        &mut self,
        il: &InteractionLoop,
        k: usize,
        geom_entries: &mut Option<Vec<Entry<ShapeClass, ShapeClass, GeomFunctor>>>,
    ) -> Result<(), String> {
        if self.interactions.list[k].functor != GeomFunctor::Unresolved {
            return Ok(());
        }
        let (id1, id2) = {
            let it = &self.interactions.list[k];
            (it.id1 as usize, it.id2 as usize)
        };
        let entries = geom_entries.get_or_insert_with(|| il.geom_entries());
        let (c1, c2) = (&self.bodies.shape[id1], &self.bodies.shape[id2]);
        let found =
            dispatch::resolve(entries, true, c1.class(), c2.class(), Some, Some).map_err(|e| {
                let (n1, n2) = (c1.class_name(), c2.class_name());
                format!("{} for {}+{} (#{}+#{})", e, n1, n2, id1, id2)
            })?;
        let it = &mut self.interactions.list[k];
        match found {
            None => it.functor = GeomFunctor::Missing,
            Some((f, swap)) => {
                it.functor = f;
                if swap {
                    it.swap_order();
                }
            }
        }
        Ok(())
    }

    /// One slot of `InteractionLoop::action`: geometry, physics, law.
    #[inline(always)]
    fn visit(
        &mut self,
        il: &mut InteractionLoop,
        k: usize,
        ctx0: &GeomCtx,
        energy: &mut LawEnergy<'_>,
        geom_entries: &mut Option<Vec<Entry<ShapeClass, ShapeClass, GeomFunctor>>>,
    ) -> Result<(), String> {
        // a potential sphere-sphere pair seen before: YADE's distance pre-check from the compact
        // summary alone (same operands, so the same decision), without touching the interaction
        let sc = &mut self.interactions.scan[k];
        if sc.idle {
            if let Some(p) = il.idle_params() {
                debug_assert!({
                    let it = &self.interactions.list[k];
                    !it.is_real()
                        && Some(it.functor) == il.idle_functor()
                        && (it.id1, it.id2, it.cell_dist) == (sc.id1, sc.id2, sc.cell_dist)
                });
                if idle_apart(p, &self.bodies, self.cell.as_ref(), &self.idle_skip, sc) {
                    return Ok(());
                }
            }
            sc.idle = false;
        } else if sc.idle_gc {
            // a potential sphere-connection pair still apart by the bound, whose sphere has no
            // real connection contact to take over (see `idle_skip`)
            debug_assert!({
                let it = &self.interactions.list[k];
                !it.is_real()
                    && it.functor == GeomFunctor::SphereGridConnection
                    && (it.id1, it.id2, it.cell_dist) == (sc.id1, sc.id2, sc.cell_dist)
            });
            if il.uses_idle_skip() && self.idle_skip.skips_gridco(sc) {
                return Ok(());
            }
            sc.idle_gc = false;
        }
        self.resolve_functor(il, k, geom_entries)?;
        if self.interactions.list[k].functor == GeomFunctor::Missing {
            return Ok(());
        }
        let (id1, id2, was_real, functor, cell_dist) = {
            let it = &self.interactions.list[k];
            (
                it.id1 as usize,
                it.id2 as usize,
                it.is_real(),
                it.functor,
                it.cell_dist,
            )
        };
        let (shift2, ctx) = period_shifts(self.cell.as_ref(), &cell_dist, ctx0.dt);
        let touches_conn = self.touches_conn(functor, id1, id2);
        // fast path for the common sphere-sphere contact; every other functor goes through
        // `geometry`
        let created = match (functor, &self.bodies.shape[id1], &self.bodies.shape[id2]) {
            (
                GeomFunctor::SphereSphere,
                Shape::Sphere { radius: r1 },
                Shape::Sphere { radius: r2 },
            ) if !was_real
                && !geom::sphere_sphere::within_reach(
                    il.sphere_sphere.as_ref().unwrap(),
                    *r1,
                    *r2,
                    &self.bodies.pos[id1],
                    &self.bodies.pos[id2],
                    &shift2,
                ) =>
            {
                false
            }
            (
                GeomFunctor::SphereSphere,
                Shape::Sphere { radius: r1 },
                Shape::Sphere { radius: r2 },
            ) => {
                let pr = Pair::of(&self.bodies, id1, id2, shift2, was_real, ctx);
                geom::sphere_sphere::go(
                    il.sphere_sphere.as_ref().unwrap(),
                    *r1,
                    *r2,
                    &pr,
                    &mut self.interactions.list[k].geom,
                )
            }
            _ => self.geometry(il, k, functor, id1, id2, was_real, &shift2, &ctx)?,
        };
        if !created {
            if was_real {
                self.interactions.list[k].reset();
            } else if Some(functor) == il.idle_functor() {
                self.interactions.scan[k] = crate::interaction::ScanEntry {
                    id1: id1 as u32,
                    id2: id2 as u32,
                    cell_dist,
                    idle: true,
                    idle_gc: false,
                    gen: 0,
                    deadline: f64::NEG_INFINITY,
                };
            } else if functor == GeomFunctor::SphereGridConnection {
                self.idle_gridco(k, id1 as u32, id2 as u32, cell_dist, &shift2);
            }
            return Ok(());
        }
        if touches_conn && !was_real {
            self.idle_skip.gained_grid_real(id1 as u32, id2 as u32);
        }
        // A plain contact (ScGeom + FrictPhys, no extension) already has its physics: the
        // FrictPhys Ip2 would return at once and the law is Cundall-Strack; skip both dispatches.
        let plain = {
            let it = &self.interactions.list[k];
            it.ext.is_none() && it.phys.is_some() && il.cundall_strack.is_some()
        };
        if !plain {
            self.physics(il, k, id1, id2)?;
        }
        let it = &mut self.interactions.list[k];
        if !was_real {
            it.iter_made_real = self.iter;
        }
        let keep = if plain {
            let energy_arg = if self.track_energy {
                energy.functor = LawFunctor::CundallStrack;
                energy.trace = false;
                Some(&mut *energy)
            } else {
                None
            };
            let b = &self.bodies;
            let lb = LawBodies {
                pos1: &b.pos[id1],
                pos2_shifted: b.pos[id2] + shift2,
            };
            law::go(
                il.cundall_strack.as_ref().unwrap(),
                it.geom.as_ref().unwrap(),
                it.phys.as_mut().unwrap(),
                id1,
                id2,
                &lb,
                &mut self.forces,
                energy_arg,
            )
        } else {
            let keep = self.law(il, k, id1, id2, &shift2, energy)?;
            if self.interactions.share_of(k) != 0 {
                self.interactions.sync_shared(k);
            }
            keep
        };
        if !keep {
            self.interactions.list[k].reset();
        }
        Ok(())
    }

    /// Slot `k` when it is a potential sphere-connection pair (its idle bound passed, or checked
    /// each step) that `geom::grid::sphere_gridco_stays_apart` shows stays potential: what `visit`
    /// does then, without the functor's working copies (the pair's new idle bound, `idle_gridco`).
    /// False, with nothing done, when that does not hold.
    #[inline(always)]
    fn apart_gridco(&mut self, cfg: &PreCfg, k: usize) -> bool {
        if cfg.gridco.is_none() {
            return false;
        }
        let it = &self.interactions.list[k];
        let sc = &self.interactions.scan[k];
        if it.functor != GeomFunctor::SphereGridConnection
            || it.geom.is_some()
            || it.phys.is_some()
            || sc.idle
        {
            return false;
        }
        let (id1, id2, cell_dist) = (it.id1, it.id2, it.cell_dist);
        let Some(partners) = self.idle_skip.grid_partners(id1) else {
            return false;
        };
        let (shift2, _) = cfg.shifts(self.cell.as_ref(), &cell_dist);
        let (b, cell) = (&self.bodies, self.cell.as_ref());
        let intrs = &self.interactions;
        if !geom::grid::sphere_gridco_stays_apart(intrs, b, cell, (id1, id2), &shift2, partners) {
            return false;
        }
        self.idle_gridco(k, id1, id2, cell_dist, &shift2);
        true
    }

    /// Whether an interaction of `functor` between `id1` and `id2` involves a `GridConnection`: when
    /// real, its bodies are marked for the idle skip (a neighbouring connection pair of the sphere
    /// may take it over).
    #[inline(always)]
    fn touches_conn(&self, functor: GeomFunctor, id1: usize, id2: usize) -> bool {
        functor == GeomFunctor::SphereGridConnection
            || matches!(self.bodies.shape[id1], Shape::GridConnection(_))
            || matches!(self.bodies.shape[id2], Shape::GridConnection(_))
    }

    /// A potential sphere-connection pair just checked and left potential: idle from now on, with
    /// the deadline of its distance beyond contact (none when the sphere is no plain sphere).
    fn idle_gridco(&mut self, k: usize, id1: u32, id2: u32, cell_dist: [i32; 3], shift2: &Vec3) {
        let skip = &self.idle_skip;
        let reach = skip.sphere_radius(id1).and_then(|r| {
            geom::grid::sphere_gridco_reach(&self.bodies, self.cell.as_ref(), id1, id2, r, shift2)
        });
        let (deadline, beyond) = reach.map_or((f64::NEG_INFINITY, None), |r| {
            (skip.deadline(&r.sphere, &r.nearest, r.reach), r.beyond)
        });
        // beyond an end of the connection, the pair takes nothing over while it stays there
        let beyond = beyond.map_or(f64::NEG_INFINITY, |(a, b)| {
            deadline.min(skip.beyond_deadline(&a, &b))
        });
        // and by the take-over tests of the sphere's real neighbour contacts
        let mut deadline = deadline;
        if deadline > f64::NEG_INFINITY {
            let found = geom::grid::takeover_operands(
                &self.interactions,
                &self.bodies,
                (id1, id2),
                shift2,
                skip.grid_partners(id1),
                |a, b| deadline = deadline.min(skip.behind_deadline(a, b)),
            );
            if found.is_none() {
                deadline = f64::NEG_INFINITY;
            }
        }
        // the longer of the two, free of the sphere's gains when beyond an end
        let (deadline, gen) = if beyond >= deadline && beyond > f64::NEG_INFINITY {
            (beyond, crate::idle_skip::GEN_FREE)
        } else {
            (deadline, skip.grid_gen(id1))
        };
        self.interactions.scan[k] = crate::interaction::ScanEntry {
            id1,
            id2,
            cell_dist,
            idle: false,
            idle_gc: true,
            gen,
            deadline,
        };
    }

    /// The thread pool for `threads` (built on first use, rebuilt when `threads` changes); None for
    /// one thread.
    fn pool_for_threads(&mut self) -> Option<std::sync::Arc<rayon::ThreadPool>> {
        if self.threads <= 1 {
            return None;
        }
        if self.pool.0.as_ref().map(|p| p.current_num_threads()) != Some(self.threads) {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(self.threads)
                .build()
                .ok()?;
            self.pool = Pool(Some(std::sync::Arc::new(pool)));
        }
        self.pool.0.clone()
    }

    /// What `pre_slot` may evaluate outside the container-order walk this step; None when it
    /// cannot help (energy tracking, or neither steady-contact kind has its functors).
    fn pre_cfg(&self, il: &InteractionLoop, serial: bool) -> Result<Option<PreCfg>, String> {
        if self.energy_wanted(il) {
            return Ok(None);
        }
        let ss_cs = match (il.sphere_sphere, il.cundall_strack) {
            (Some(ss), Some(cs)) => Some((ss, cs)),
            _ => None,
        };
        // a steady ScGeom6D + CohFrictPhys contact: the Ip2 is a no-op on existing physics while
        // no `setCohesionNow` is pending (per contact: no `initCohesion`), the law is CohesionMoment
        // and cannot fail (its one error, twist creep with the incremental form, is a parameter check)
        let steady_coh = |g: GeomClass| -> Result<Option<law::cohesion_moment::Params>, String> {
            Ok(match il.cohesion_moment {
                Some(cm)
                    if !(cm.twist_creep && cm.use_incremental_form)
                        && il
                            .cohfrict_phys
                            .as_ref()
                            .is_some_and(|p| !p.set_cohesion_now)
                        && il.law_functor(g, PhysClass::CohFrictPhys)?
                            == Some(LawFunctor::CohesionMoment)
                        && il
                            .phys_functor(MatClass::CohFrictMat, MatClass::CohFrictMat)?
                            .map(|(f, _)| f)
                            == Some(PhysFunctor::CohFrict) =>
                {
                    Some(cm)
                }
                _ => None,
            })
        };
        let six_d = match il.sphere_sphere_6d {
            Some(p6) => steady_coh(GeomClass::ScGeom6D)?.map(|cm| (p6, cm)),
            None => None,
        };
        // a node-node bond likewise, in the serial walk only: its geometry moves the connection
        // body (`GridNodeGeom6D.connectionBody`), which the event does at its turn
        let grid_6d = match il.gridnode_gridnode {
            Some(p6) if serial => steady_coh(GeomClass::GridNodeGeom6D)?.map(|cm| (p6, cm)),
            _ => None,
        };
        // (a functor lookup that fails here leaves the lean path out: the visit reports it, if
        // the walk meets such a pair at all)
        let gridco = match il.scgridco_frict {
            Some(p)
                if serial
                    && self.idle_skip.grid_partners_noted()
                    && il.sphere_gridco.is_some()
                    && il
                        .law_functor(GeomClass::ScGridCoGeom, PhysClass::FrictPhys)
                        .ok()
                        .flatten()
                        == Some(LawFunctor::ScGridCoFrict) =>
            {
                let m = &self.materials;
                let mut frict = Vec::with_capacity(m.len() * m.len());
                for a in m {
                    for b in m {
                        let f = il.phys_functor(a.class(), b.class()).ok().flatten();
                        frict.push(f.is_some_and(|(f, _)| f == PhysFunctor::Frict));
                    }
                }
                Some(GridcoCfg { p, frict })
            }
            _ => None,
        };
        if ss_cs.is_none() && six_d.is_none() && grid_6d.is_none() && gridco.is_none() {
            return Ok(None);
        }
        Ok(Some(PreCfg {
            idle: il.idle_params().copied(),
            ss_cs,
            six_d,
            gridco,
            coh_mat: self
                .materials
                .iter()
                .map(|m| m.class() == MatClass::CohFrictMat)
                .collect(),
            zero_shift: period_shifts(self.cell.as_ref(), &[0; 3], self.dt),
            bond_lanes: il.bond_lanes
                && grid_6d.is_some_and(|(p6, _)| p6.update_rotations)
                && crate::fast::lanes_available(),
            grid_6d,
            dt: self.dt,
            iter: self.iter,
        }))
    }

    /// With `threads > 1`, the part of every slot's work that depends only on positions,
    /// velocities and the slot's own state, in parallel runs of slots: idle sphere-sphere pairs
    /// still apart are dropped, and the steady sphere-sphere contacts (real; ScGeom + FrictPhys +
    /// Cundall-Strack, or ScGeom6D + CohFrictPhys + CohesionMoment) get their geometry (always
    /// true or an erasure on a real interaction) and law arithmetic (`law::load`,
    /// `law::cohesion_moment::load`). The caller then walks the events in container order: loads
    /// added, erasures done, other slots visited as in the serial loop, so every body's sums are
    /// YADE's. Safe because nothing the serial visits do changes what these read: they write
    /// forces, their own interaction, sphere-connection interactions (the grid hand-over) and
    /// connection positions (`GridNodeGeom6D`), never a sphere's kinematics or a sphere-sphere
    /// contact. None: serial loop (one thread, energy tracking, too few slots, or no steady kind).
    fn pre_pass(&mut self, il: &InteractionLoop) -> Result<Option<Vec<Vec<Event>>>, String> {
        if self.interactions.list.len() < self.par_min_slots || self.threads <= 1 {
            return Ok(None);
        }
        let Some(cfg) = self.pre_cfg(il, false)? else {
            return Ok(None);
        };
        let Some(pool) = self.pool_for_threads() else {
            return Ok(None);
        };
        let b = &self.bodies;
        let cell = self.cell.as_ref();
        let skip = &self.idle_skip;
        let scan = &mut self.interactions.scan;
        let list = &mut self.interactions.list;
        const RUN: usize = 2048;
        let runs = pool.install(|| {
            use rayon::prelude::*;
            list.par_chunks_mut(RUN)
                .zip(scan.par_chunks_mut(RUN))
                .enumerate()
                .map(|(c, (its, sc_run))| {
                    let k0 = c * RUN;
                    let mut events = Vec::with_capacity(its.len());
                    for j in 0..its.len() {
                        const AHEAD: usize = 24;
                        if j + AHEAD < its.len() && !sc_run[j + AHEAD].is_idle() {
                            crate::interaction::prefetch(&its[j + AHEAD]);
                        }
                        if j + EXT_AHEAD < its.len() && !sc_run[j + EXT_AHEAD].is_idle() {
                            crate::interaction::prefetch_ext(&its[j + EXT_AHEAD]);
                        }
                        let k = (k0 + j) as u32;
                        if let Some(ev) =
                            pre_slot(&cfg, b, cell, skip, k, &mut sc_run[j], &mut its[j])
                        {
                            events.push(ev);
                        }
                    }
                    events
                })
                .collect::<Vec<_>>()
        });
        Ok(Some(runs))
    }

    /// The geometry functor of interaction `k` (`IGeomFunctor::go`); true when a geometry exists now.
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    fn geometry(
        &mut self,
        il: &mut InteractionLoop,
        k: usize,
        functor: GeomFunctor,
        id1: usize,
        id2: usize,
        was_real: bool,
        shift2: &Vec3,
        ctx: &GeomCtx,
    ) -> Result<bool, String> {
        let b = &self.bodies;
        let radius = |id: usize| -> Result<f64, String> {
            b.shape[id].sphere_radius().ok_or_else(|| {
                format!(
                    "internal: functor {:?} needs a sphere, #{} is a {}",
                    functor,
                    id,
                    b.shape[id].class_name()
                )
            })
        };
        if functor == GeomFunctor::SphereGridConnection {
            return geom::grid::sphere_gridco(
                k,
                &mut self.interactions,
                b,
                self.cell.as_ref(),
                ctx,
                shift2,
                self.idle_skip.grid_partners(id1 as u32),
            );
        }
        let pr = Pair::of(b, id1, id2, *shift2, was_real, *ctx);
        let it = &mut self.interactions.list[k];
        let g = &mut it.geom;
        let mut conn_sync = None;
        let created = match (functor, &b.shape[id1], &b.shape[id2]) {
            (GeomFunctor::SphereSphere, _, _) => geom::sphere_sphere::go(
                il.sphere_sphere.as_ref().unwrap(),
                radius(id1)?,
                radius(id2)?,
                &pr,
                g,
            ),
            (GeomFunctor::FacetSphere, Shape::Facet(f), _) => {
                geom::facet_sphere::go(il.facet_sphere.as_mut().unwrap(), f, radius(id2)?, &pr, g)
            }
            (GeomFunctor::WallSphere, Shape::Wall { axis, sense }, _) => geom::wall_sphere::go(
                il.wall_sphere.as_ref().unwrap(),
                *axis,
                *sense,
                radius(id2)?,
                &pr,
                g,
            ),
            (GeomFunctor::BoxSphere, Shape::Box { extents }, _) => {
                let p = il.box_sphere.as_ref().unwrap();
                if p.six_d {
                    geom::box_sphere::go_6d(p, extents, radius(id2)?, &pr, g, &mut it.ext)
                } else {
                    geom::box_sphere::go(p, extents, radius(id2)?, &pr, g)
                }
            }
            (GeomFunctor::SphereSphere6D, _, _) => geom::grid::six_d(
                il.sphere_sphere_6d.as_ref().unwrap(),
                radius(id1)?,
                radius(id2)?,
                &pr,
                g,
                &mut it.ext,
                false,
                &mut conn_sync,
            ),
            (GeomFunctor::GridNodeGridNode, _, _) => geom::grid::six_d(
                il.gridnode_gridnode.as_ref().unwrap(),
                radius(id1)?,
                radius(id2)?,
                &pr,
                g,
                &mut it.ext,
                true,
                &mut conn_sync,
            ),
            (
                GeomFunctor::GridConnectionGridConnection,
                Shape::GridConnection(c1),
                Shape::GridConnection(c2),
            ) => geom::grid::gridco_gridco(b, c1, c2, ctx, shift2, g, &mut it.ext),
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
        // GridNodeGeom6D.connectionBody follows node 1 (the only thing that moves a connection)
        if let Some((cb, pos)) = conn_sync {
            self.bodies.pos[cb as usize] = pos;
        }
        Ok(created)
    }

    /// The physics functor (`IPhysFunctor::go`), dispatched on the material classes.
    #[inline(never)]
    fn physics(
        &mut self,
        il: &mut InteractionLoop,
        k: usize,
        id1: usize,
        id2: usize,
    ) -> Result<(), String> {
        let b = &self.bodies;
        let m1 = &self.materials[b.material[id1]];
        let m2 = &self.materials[b.material[id2]];
        let it = &mut self.interactions.list[k];
        let found = il.phys_functor(m1.class(), m2.class())?;
        let swapped = found.is_some_and(|(_, s)| s);
        match found.map(|(f, _)| f) {
            Some(PhysFunctor::Cpm) => {
                if it.phys.is_none() {
                    let (fp, cp) = phys::ip2_cpm(m1, m2, self.iter, il.cpm_phys.unwrap_or(10))?;
                    it.phys = Some(fp);
                    it.ext_mut().cpm = Some(Box::new(cp));
                }
            }
            Some(PhysFunctor::FrictCpm) => {
                // Ip2_FrictMat_CpmMat_FrictPhys (Ip2_FrictMat_FrictMat_FrictPhys's formulas); with the
                // CpmMat body first the dispatcher would swap the materials, which Debian's YADE
                // stops on (InteractionLoop::action, `assert(!swap)`): refused alike
                if swapped {
                    return Err(format!(
                        "Ip2_FrictMat_CpmMat_FrictPhys for #{} ({}) + #{} ({}): the physics functor needs the materials swapped, and YADE 2023.02a aborts there (InteractionLoop: assert(!swap)); ryade refuses it too",
                        id1,
                        m1.class_name(),
                        id2,
                        m2.class_name()
                    ));
                }
                if it.phys.is_none() {
                    it.phys = Some(phys::ip2_frict(m1, m2, it.geom.as_ref().unwrap()));
                }
            }
            Some(PhysFunctor::Frict) => {
                if it.phys.is_none() {
                    it.phys = Some(phys::ip2_frict(m1, m2, it.geom.as_ref().unwrap()));
                }
            }
            Some(PhysFunctor::CohFrict) => {
                let ip2 = il.cohfrict_phys.as_mut().unwrap();
                let g = it.geom.as_ref().unwrap();
                let (r1, r2) = (g.radius1, g.radius2);
                let e = it.ext.get_or_insert_with(Default::default);
                let act = ip2.go(self.iter, m1, m2, r1, r2, &mut it.phys, &mut e.coh);
                if act == phys::CohAction::InitRotations {
                    if let Some(rot) = e.geom.as_mut().and_then(|g| g.rot_mut()) {
                        rot.init_rotations(&b.ori[id1], &b.ori[id2]);
                    }
                }
            }
            Some(PhysFunctor::ViscEl) => {
                if it.phys.is_none() {
                    let (fp, vp) = phys::ip2_viscel(
                        &il.viscel_ip2,
                        m1,
                        m2,
                        b.mass[id1],
                        b.mass[id2],
                        it.geom.as_ref().unwrap(),
                        (id1, id2),
                    )?;
                    it.phys = Some(fp);
                    it.ext_mut().viscel = Some(vp);
                }
            }
            Some(PhysFunctor::Bubble) => {
                if it.phys.is_none() {
                    it.phys = Some(phys::FrictPhys::default());
                    it.ext_mut().bubble = Some(phys::BubblePhys::default());
                }
            }
            Some(PhysFunctor::Luding) => {
                if it.phys.is_none() {
                    let (fp, lp) = phys::ip2_luding(
                        m1,
                        m2,
                        b.shape[id1].sphere_radius(),
                        b.shape[id2].sphere_radius(),
                    )?;
                    it.phys = Some(fp);
                    it.ext_mut().luding = Some(lp);
                }
            }
            Some(PhysFunctor::Mindlin) => {
                if it.phys.is_none() {
                    let (fp, mp) = phys::ip2_mindlin(
                        il.mindlin_phys.as_ref().unwrap(),
                        m1,
                        m2,
                        it.geom.as_ref().unwrap(),
                    )?;
                    it.phys = Some(fp);
                    it.ext_mut().mindlin = Some(mp);
                }
            }
            None => {
                return Err(format!(
                    "Undefined IPhys dispatch for materials of #{} and #{} ({} and {}): add {}",
                    id1,
                    id2,
                    m1.class_name(),
                    m2.class_name(),
                    if m1.class() == MatClass::CohFrictMat && m2.class() == MatClass::CohFrictMat {
                        "Ip2_CohFrictMat_CohFrictMat_CohFrictPhys()"
                    } else if m1.class() == MatClass::ViscElMat && m2.class() == MatClass::ViscElMat
                    {
                        "Ip2_ViscElMat_ViscElMat_ViscElPhys()"
                    } else {
                        "Ip2_FrictMat_FrictMat_FrictPhys()"
                    }
                ))
            }
        }
        Ok(())
    }

    /// The law functor (`LawFunctor::go`), dispatched on the geometry and physics classes; false
    /// when the interaction must be erased.
    #[inline(never)]
    fn law(
        &mut self,
        il: &mut InteractionLoop,
        k: usize,
        id1: usize,
        id2: usize,
        shift2: &Vec3,
        energy: &mut LawEnergy<'_>,
    ) -> Result<bool, String> {
        let b = &self.bodies;
        let it = &mut self.interactions.list[k];
        let gc = it.geom_class().unwrap();
        let pc = it.phys_class();
        let Some(lf) = il.law_functor(gc, pc)? else {
            return Err(format!(
                "None of the given Law2 functors can handle interaction #{}+#{} ({}, {:?}): add {}",
                id1,
                id2,
                gc.name(),
                pc,
                match (gc, pc) {
                    (GeomClass::ScGridCoGeom, PhysClass::FrictPhys) =>
                        "Law2_ScGridCoGeom_FrictPhys_CundallStrack()",
                    (GeomClass::GridCoGridCoGeom, _) =>
                        "Law2_GridCoGridCoGeom_FrictPhys_CundallStrack()",
                    (_, PhysClass::CohFrictPhys) => "Law2_ScGeom6D_CohFrictPhys_CohesionMoment()",
                    (_, PhysClass::ViscElPhys) => "Law2_ScGeom_ViscElPhys_Basic()",
                    (_, PhysClass::MindlinPhys) => "Law2_ScGeom_MindlinPhys_Mindlin()",
                    (_, PhysClass::LudingPhys) => "Law2_ScGeom_LudingPhys_Basic()",
                    (_, PhysClass::BubblePhys) => "Law2_ScGeom_BubblePhys_Bubble()",
                    (_, PhysClass::CpmPhys) => "Law2_ScGeom_CpmPhys_Cpm()",
                    _ => "Law2_ScGeom_FrictPhys_CundallStrack()",
                }
            ));
        };
        // the law adds to O.energy while trackEnergy; a GridCoGridCo law with traceEnergy takes its
        // energy branch in any case (Grid.cpp)
        let trace = lf == LawFunctor::GridCoGridCoFrict
            && il.gridco_gridco_frict.is_some_and(|p| p.trace_energy);
        let energy = if self.track_energy || trace {
            energy.functor = lf;
            energy.trace = trace;
            Some(energy)
        } else {
            None
        };
        let g = *it.geom.as_ref().unwrap();
        let fresh = it.iter_made_real == self.iter;
        let ph = it.phys.as_mut().unwrap();
        let bad = |what: &str| format!("internal: {} without {}", lf.class_name(), what);
        Ok(match lf {
            LawFunctor::CundallStrack => {
                let lb = LawBodies {
                    pos1: &b.pos[id1],
                    pos2_shifted: b.pos[id2] + shift2,
                };
                law::go(
                    il.cundall_strack.as_ref().unwrap(),
                    &g,
                    ph,
                    id1,
                    id2,
                    &lb,
                    &mut self.forces,
                    energy,
                )
            }
            LawFunctor::CohesionMoment => {
                let e = it.ext.as_mut().ok_or_else(|| bad("extension"))?;
                let rot = e
                    .geom
                    .as_mut()
                    .and_then(|g| g.rot_mut())
                    .ok_or_else(|| bad("ScGeom6D"))?;
                let cp = e.coh.as_mut().ok_or_else(|| bad("CohFrictPhys"))?;
                let lb = coh_bodies(b, id1, id2, shift2);
                let p = il.cohesion_moment.as_ref().unwrap();
                match law::cohesion_moment::load(p, self.dt, fresh, &g, rot, ph, cp, &lb, energy)? {
                    Some(l) => {
                        law::cohesion_moment::apply(&mut self.forces, id1, id2, &l);
                        true
                    }
                    None => false,
                }
            }
            LawFunctor::ScGridCoFrict | LawFunctor::ScGridCoCohFrict => {
                let e = it.ext.as_mut().ok_or_else(|| bad("extension"))?;
                let Some(geom::GeomExt::ScGridCo(x)) = e.geom else {
                    return Err(bad("ScGridCoGeom"));
                };
                if lf == LawFunctor::ScGridCoFrict {
                    law::grid::scgridco_frict(
                        il.scgridco_frict.as_ref().unwrap(),
                        &g,
                        &x,
                        ph,
                        id1,
                        id2,
                        &mut self.forces,
                        energy,
                    )
                } else {
                    let cp = e.coh.as_mut().ok_or_else(|| bad("CohFrictPhys"))?;
                    law::grid::scgridco_cohfrict(
                        fresh,
                        &g,
                        &x,
                        ph,
                        cp,
                        id1,
                        id2,
                        &mut self.forces,
                        energy,
                    )
                }
            }
            LawFunctor::ViscElBasic => {
                let vp = it
                    .ext
                    .as_mut()
                    .and_then(|e| e.viscel.as_mut())
                    .ok_or_else(|| bad("ViscElPhys"))?;
                let vb = two_bodies(b, self.cell.as_ref(), &it.cell_dist, shift2, id1, id2);
                let l = law::viscel::load(self.dt, fresh, &g, ph, vp, &vb);
                apply_or_erase(&mut self.forces, id1, id2, l)
            }
            LawFunctor::Bubble => {
                let bp = it
                    .ext
                    .as_mut()
                    .and_then(|e| e.bubble.as_mut())
                    .ok_or_else(|| bad("BubblePhys"))?;
                let l = law::bubble::load(
                    il.bubble.as_mut().unwrap(),
                    fresh,
                    &g,
                    ph,
                    bp,
                    &b.pos[id1],
                    &b.pos[id2],
                    self.cell.is_some(),
                )?;
                apply_or_erase(&mut self.forces, id1, id2, l)
            }
            LawFunctor::Cpm => {
                let cp = it
                    .ext
                    .as_mut()
                    .and_then(|e| e.cpm.as_deref_mut())
                    .ok_or_else(|| bad("CpmPhys"))?;
                let fresh = if fresh {
                    let plane = |s: &Shape| {
                        matches!(s, Shape::Facet(_) | Shape::Wall { .. } | Shape::Box { .. })
                    };
                    let (s1, s2) = (&b.shape[id1], &b.shape[id2]);
                    Some(match (s1, s2) {
                        (Shape::Sphere { .. }, Shape::Sphere { .. }) => law::cpm::Fresh::Spheres {
                            pos1: b.pos[id1],
                            pos2: b.pos[id2],
                            shift2: *shift2,
                        },
                        (Shape::Sphere { radius }, s) | (s, Shape::Sphere { radius })
                            if plane(s) =>
                        {
                            law::cpm::Fresh::SphereOnPlane { radius: *radius }
                        }
                        _ => {
                            return Err(format!(
                                "Law2_ScGeom_CpmPhys_Cpm on {}+{} (#{}+#{}): YADE leaves the contact's lengths NaN there; ryade supports spheres against spheres, facets, walls and boxes",
                                s1.class_name(),
                                s2.class_name(),
                                id1,
                                id2
                            ))
                        }
                    })
                } else {
                    None
                };
                let arms = if self.cell.is_some() {
                    law::cpm::Arms::Periodic
                } else {
                    law::cpm::Arms::ContactPoint {
                        pos1: b.pos[id1],
                        pos2: b.pos[id2],
                    }
                };
                match law::cpm::load(il.cpm.as_ref().unwrap(), fresh, &g, ph, cp, arms)? {
                    law::cpm::Outcome::Load(l) => {
                        law::apply(&mut self.forces, id1, id2, &l);
                        true
                    }
                    law::cpm::Outcome::Broken => false,
                }
            }
            LawFunctor::LudingBasic => {
                let lp = it
                    .ext
                    .as_mut()
                    .and_then(|e| e.luding.as_mut())
                    .ok_or_else(|| bad("LudingPhys"))?;
                let vb = two_bodies(b, self.cell.as_ref(), &it.cell_dist, shift2, id1, id2);
                let l = law::luding::load(self.dt, fresh, &g, ph, lp, &vb);
                apply_or_erase(&mut self.forces, id1, id2, l)
            }
            LawFunctor::Mindlin => {
                let mp = it
                    .ext
                    .as_mut()
                    .and_then(|e| e.mindlin.as_mut())
                    .ok_or_else(|| bad("MindlinPhys"))?;
                let (shift_vel, shift2) = shifts(self.cell.as_ref(), &it.cell_dist, shift2);
                let mb = law::mindlin::Bodies {
                    s1: geom::Kin::of(b, id1),
                    s2: geom::Kin::of(b, id2),
                    mass1: b.mass[id1],
                    mass2: b.mass[id2],
                    dynamic1: b.is_dynamic(id1),
                    dynamic2: b.is_dynamic(id2),
                    shift2,
                    shift_vel,
                    periodic: self.cell.is_some(),
                };
                match law::mindlin::load(il.mindlin.as_ref().unwrap(), self.dt, &g, ph, mp, &mb) {
                    law::mindlin::Outcome::Erase => false,
                    law::mindlin::Outcome::Keep => true,
                    law::mindlin::Outcome::Apply(l, moment) => {
                        law::apply(&mut self.forces, id1, id2, &l);
                        if let Some(m) = moment {
                            self.forces.add_torque(id1, &(-m));
                            self.forces.add_torque(id2, &m);
                        }
                        true
                    }
                }
            }
            LawFunctor::GridCoGridCoFrict => {
                let Some(geom::GeomExt::GridCoGridCo(x)) = it.geom_ext().copied() else {
                    return Err(bad("GridCoGridCoGeom"));
                };
                let nodes = |id: usize| match &b.shape[id] {
                    Shape::GridConnection(c) => Ok((c.node1 as usize, c.node2 as usize)),
                    s => Err(format!(
                        "body #{} is a {}, not a GridConnection",
                        id,
                        s.class_name()
                    )),
                };
                let (n1, n2) = (nodes(id1)?, nodes(id2)?);
                let ph = it.phys.as_mut().unwrap();
                law::grid::gridco_gridco_frict(
                    il.gridco_gridco_frict.as_ref().unwrap(),
                    &g,
                    &x,
                    ph,
                    n1,
                    n2,
                    &mut self.forces,
                    energy,
                )
            }
        })
    }
}

/// What the serial part of the threaded loop does with a slot, in container order
/// (`Scene::pre_pass`); idle pairs still apart leave no event.
#[derive(Clone, Copy, Debug)]
enum Event {
    /// Left to the serial loop (`Scene::visit`).
    Visit(u32),
    /// A steady contact evaluated: add this load to bodies `id1`, `id2`.
    Load(u32, u32, law::Load),
    /// A steady cohesive-frictional contact evaluated: add this load to bodies `id1`, `id2`.
    CohLoad(u32, u32, law::cohesion_moment::CohLoad),
    /// A steady node-node bond evaluated: move the connection body to this position (when the
    /// bond has one), then add the load to nodes `id1`, `id2`.
    BondLoad(u32, u32, law::cohesion_moment::CohLoad, Option<(u32, Vec3)>),
    /// Slot `k`: a steady contact the law erases.
    Erase(u32),
}

/// True when an idle sphere-sphere pair is still apart, so its visit ends here: by `skip`'s bound
/// without reading the bodies, or by YADE's distance pre-check from the compact summary alone
/// (same operands as `Ig2_Sphere_Sphere_ScGeom::go`, so the same decision), which also renews the
/// pair's deadline. False also when the bodies are no longer both plain spheres.
#[inline(always)]
fn idle_apart(
    p: &geom::sphere_sphere::Params,
    b: &Bodies,
    cell: Option<&Cell>,
    skip: &IdleSkip,
    sc: &mut crate::interaction::ScanEntry,
) -> bool {
    if skip.skips(sc) {
        return true;
    }
    let Some((r1, r2)) = skip.sphere_radii(sc.id1, sc.id2) else {
        return false;
    };
    // a zero period gives a zero shift (its sign cannot change the squared distance)
    let shift2 = match cell {
        Some(c) if sc.cell_dist != [0; 3] => c.shift_pos(&sc.cell_dist),
        _ => Vec3::zeros(),
    };
    let (p1, p2) = (&b.pos[sc.id1 as usize], &b.pos[sc.id2 as usize]);
    if geom::sphere_sphere::within_reach(p, r1, r2, p1, p2, &shift2) {
        return false;
    }
    let reach = p.interaction_detection_factor * (r1 + r2);
    sc.deadline = skip.deadline(p1, &(p2 + shift2), reach);
    true
}

/// How many slots ahead the interaction loop asks for an interaction's extension (its interaction
/// was asked for 24 slots ahead, so the pointer is in cache by then).
const EXT_AHEAD: usize = 8;

/// What `Scene::steady_gridco` may take: Law2_ScGridCoGeom_FrictPhys_CundallStrack's parameters, and
/// per pair of materials (row-major) whether their physics functor is
/// Ip2_FrictMat_FrictMat_FrictPhys, which leaves existing physics alone. (A contact with a
/// CohFrictPhys is left to the visit: where grids are, CohesionMoment is registered for the bonds,
/// and it is that contact's law.)
struct GridcoCfg {
    p: law::grid::ScGridCoParams,
    frict: Vec<bool>,
}

/// What the pre-pass may evaluate (`Scene::pre_cfg`).
struct PreCfg {
    /// The idle pairs' distance pre-check (`InteractionLoop::idle_params`).
    idle: Option<geom::sphere_sphere::Params>,
    /// Steady ScGeom + FrictPhys contacts: `Ig2_Sphere_Sphere_ScGeom`, Cundall-Strack.
    ss_cs: Option<(geom::sphere_sphere::Params, law::Params)>,
    /// Steady ScGeom6D + CohFrictPhys contacts: `Ig2_Sphere_Sphere_ScGeom6D`, CohesionMoment.
    six_d: Option<(geom::grid::SixDParams, law::cohesion_moment::Params)>,
    /// Steady GridNodeGeom6D + CohFrictPhys bonds: `Ig2_GridNode_GridNode_GridNodeGeom6D`,
    /// CohesionMoment (serial walk only).
    grid_6d: Option<(geom::grid::SixDParams, law::cohesion_moment::Params)>,
    /// Per material: a CohFrictMat (whose Ip2 leaves existing physics alone this step).
    coh_mat: Vec<bool>,
    /// Steady sphere-connection contacts (`Scene::steady_gridco`, serial walk with the grid
    /// partners noted).
    gridco: Option<GridcoCfg>,
    /// `period_shifts` of an unshifted pair, once per walk.
    zero_shift: (Vec3, GeomCtx),
    /// Runs of steady node bonds with their rotations in lanes (`Scene::steady_bonds`): AVX2, and
    /// bonds whose rotations are updated.
    bond_lanes: bool,
    dt: f64,
    iter: i64,
}

impl PreCfg {
    /// `period_shifts` for a pair of period `cd` (the unshifted one read, not recomputed).
    #[inline(always)]
    fn shifts(&self, cell: Option<&Cell>, cd: &[i32; 3]) -> (Vec3, GeomCtx) {
        match cd {
            [0, 0, 0] => self.zero_shift,
            _ => period_shifts(cell, cd, self.dt),
        }
    }
}

/// The part of slot `k`'s work that depends only on positions, velocities and its own state (see
/// `Scene::pre_pass`): None for an idle sphere-sphere pair still apart (YADE's distance pre-check,
/// same operands), the load (or erasure) of a steady contact, otherwise `Event::Visit(k)`. Each
/// step is the serial visit's (`Scene::visit`), in its order, with the dispatch already known.
#[inline(always)]
fn pre_slot(
    cfg: &PreCfg,
    b: &Bodies,
    cell: Option<&Cell>,
    skip: &IdleSkip,
    k: u32,
    sc: &mut crate::interaction::ScanEntry,
    it: &mut crate::interaction::Interaction,
) -> Option<Event> {
    if sc.idle {
        return match cfg.idle {
            Some(p) if idle_apart(&p, b, cell, skip, sc) => None,
            _ => Some(Event::Visit(k)),
        };
    }
    if sc.idle_gc || !it.is_real() {
        return Some(Event::Visit(k));
    }
    let (id1, id2) = (it.id1 as usize, it.id2 as usize);
    // a steady 6-D cohesive contact (plain spheres) or node bond: geometry and law here
    let six = match (it.functor, it.geom_ext()) {
        (GeomFunctor::SphereSphere6D, Some(geom::GeomExt::Sc6D(_))) => {
            cfg.six_d.map(|p| (p, false))
        }
        (GeomFunctor::GridNodeGridNode, Some(geom::GeomExt::GridNode { .. })) => {
            cfg.grid_6d.map(|p| (p, true))
        }
        _ => None,
    };
    if let Some(((p6, cm), grid_node)) = six {
        let Some(radii) = steady_six_radii(cfg, b, skip, it, grid_node) else {
            return Some(Event::Visit(k));
        };
        let (shift2, ctx) = cfg.shifts(cell, &it.cell_dist);
        return Some(
            match steady_six_d(
                &p6,
                &cm,
                cfg,
                b,
                (id1, id2),
                radii,
                shift2,
                ctx,
                it,
                grid_node,
            ) {
                Some((l, conn_sync)) if grid_node => {
                    Event::BondLoad(id1 as u32, id2 as u32, l, conn_sync)
                }
                Some((l, _)) => Event::CohLoad(id1 as u32, id2 as u32, l),
                None => Event::Erase(k),
            },
        );
    }
    let Some((r1, r2)) = skip.sphere_radii(it.id1, it.id2) else {
        return Some(Event::Visit(k));
    };
    let (shift2, ctx) = cfg.shifts(cell, &it.cell_dist);
    match (it.functor, cfg.ss_cs) {
        (GeomFunctor::SphereSphere, Some((ss, cs))) if it.ext.is_none() => {
            let pr = Pair::of(b, id1, id2, shift2, true, ctx);
            geom::sphere_sphere::go(&ss, r1, r2, &pr, &mut it.geom);
            let lb = LawBodies {
                pos1: &b.pos[id1],
                pos2_shifted: b.pos[id2] + shift2,
            };
            let g = it.geom.as_ref().unwrap();
            Some(
                match law::load(&cs, g, it.phys.as_mut().unwrap(), &lb, None) {
                    Some(l) => Event::Load(id1 as u32, id2 as u32, l),
                    None => Event::Erase(k),
                },
            )
        }
        _ => Some(Event::Visit(k)),
    }
}

/// The radii of a 6-D cohesive contact or node bond (`grid_node`) that `pre_slot` takes as steady:
/// both materials CohFrictMat and the cohesion set up (None otherwise: the slot is visited).
#[inline(always)]
fn steady_six_radii(
    cfg: &PreCfg,
    b: &Bodies,
    skip: &IdleSkip,
    it: &crate::interaction::Interaction,
    grid_node: bool,
) -> Option<(f64, f64)> {
    let (id1, id2) = (it.id1 as usize, it.id2 as usize);
    let radii = if grid_node {
        b.shape[id1]
            .sphere_radius()
            .zip(b.shape[id2].sphere_radius())
    } else {
        skip.sphere_radii(it.id1, it.id2)
    };
    let steady = cfg.coh_mat[b.material[id1]]
        && cfg.coh_mat[b.material[id2]]
        && it.coh().is_some_and(|c| !c.init_cohesion);
    radii.filter(|_| steady)
}

/// The radii of slot `k` when `pre_slot` takes it to `steady_six_d` as a node bond (see
/// `Scene::steady_bonds`); None for any other slot.
#[inline(always)]
fn steady_bond_radii(
    cfg: &PreCfg,
    b: &Bodies,
    skip: &IdleSkip,
    sc: &crate::interaction::ScanEntry,
    it: &crate::interaction::Interaction,
) -> Option<(f64, f64)> {
    if sc.idle || sc.idle_gc || !it.is_real() || cfg.grid_6d.is_none() {
        return None;
    }
    match (it.functor, it.geom_ext()) {
        (GeomFunctor::GridNodeGridNode, Some(geom::GeomExt::GridNode { .. })) => {
            steady_six_radii(cfg, b, skip, it, true)
        }
        _ => None,
    }
}

/// A steady node bond's event (`Event::BondLoad`): the connection body moved (when the bond has
/// one), then the load added to nodes `id1`, `id2`.
#[inline(always)]
fn apply_bond(
    bodies: &mut Bodies,
    forces: &mut Forces,
    (id1, id2): (usize, usize),
    l: &law::cohesion_moment::CohLoad,
    conn_sync: Option<(u32, Vec3)>,
) {
    if let Some((cb, pos)) = conn_sync {
        bodies.pos[cb as usize] = pos;
    }
    law::cohesion_moment::apply(forces, id1, id2, l)
}

/// A steady 6-D cohesive contact or node bond (`grid_node`; see `pre_slot`): its geometry, then
/// CohesionMoment's load with the connection body's move (a bond's), or None when either erases it.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn steady_six_d(
    p6: &geom::grid::SixDParams,
    cm: &law::cohesion_moment::Params,
    cfg: &PreCfg,
    b: &Bodies,
    (id1, id2): (usize, usize),
    (r1, r2): (f64, f64),
    shift2: Vec3,
    ctx: GeomCtx,
    it: &mut crate::interaction::Interaction,
    grid_node: bool,
) -> Option<(law::cohesion_moment::CohLoad, Option<(u32, Vec3)>)> {
    let pr = Pair::of(b, id1, id2, shift2, true, ctx);
    let mut conn_sync = None;
    if !geom::grid::six_d(
        p6,
        r1,
        r2,
        &pr,
        &mut it.geom,
        &mut it.ext,
        grid_node,
        &mut conn_sync,
    ) {
        return None;
    }
    steady_six_d_law(cm, cfg, b, (id1, id2), shift2, it, conn_sync)
}

/// The end of `steady_six_d`, after the geometry and rotations: CohesionMoment's load.
#[inline(always)]
fn steady_six_d_law(
    cm: &law::cohesion_moment::Params,
    cfg: &PreCfg,
    b: &Bodies,
    (id1, id2): (usize, usize),
    shift2: Vec3,
    it: &mut crate::interaction::Interaction,
    conn_sync: Option<(u32, Vec3)>,
) -> Option<(law::cohesion_moment::CohLoad, Option<(u32, Vec3)>)> {
    let fresh = it.iter_made_real == cfg.iter;
    let g = *it.geom.as_ref().unwrap();
    let e = it.ext.as_mut().unwrap();
    let rot = e.geom.as_mut().and_then(|g| g.rot_mut()).unwrap();
    let cp = e.coh.as_mut().unwrap();
    let lb = coh_bodies(b, id1, id2, &shift2);
    let ph = it.phys.as_mut().unwrap();
    match law::cohesion_moment::load(cm, cfg.dt, fresh, &g, rot, ph, cp, &lb, None) {
        Ok(l) => l.map(|l| (l, conn_sync)),
        // excluded by `pre_cfg` (the law's only error is a parameter check)
        Err(_) => unreachable!("CohesionMoment parameter check passed in pre_cfg"),
    }
}

/// What CohesionMoment reads of the two bodies.
#[inline(always)]
fn coh_bodies(b: &Bodies, id1: usize, id2: usize, shift2: &Vec3) -> law::cohesion_moment::Bodies2 {
    law::cohesion_moment::Bodies2 {
        pos1: b.pos[id1],
        pos2_shifted: b.pos[id2] + shift2,
        ang_vel1: b.ang_vel[id1],
        ang_vel2: b.ang_vel[id2],
    }
}

/// Body 2's period shift of position (`Cell::intrShiftPos`) and the geometry context with its
/// shift of velocity (`intrShiftVel`); zeros without a periodic cell.
#[inline(always)]
fn period_shifts(cell: Option<&Cell>, cell_dist: &[i32; 3], dt: f64) -> (Vec3, GeomCtx) {
    match cell {
        Some(c) => (
            c.shift_pos(cell_dist),
            GeomCtx {
                dt,
                shift_vel: c.shift_vel(cell_dist),
            },
        ),
        None => (
            Vec3::zeros(),
            GeomCtx {
                dt,
                shift_vel: Vec3::zeros(),
            },
        ),
    }
}

/// Body 2's period shift of velocity and position (zeros without a periodic cell).
fn shifts(cell: Option<&Cell>, cell_dist: &[i32; 3], shift2: &Vec3) -> (Vec3, Vec3) {
    match cell {
        Some(c) => (c.shift_vel(cell_dist), *shift2),
        None => (Vec3::zeros(), Vec3::zeros()),
    }
}

/// The two bodies' kinematics as the viscous laws read them (ViscEl, Luding).
fn two_bodies(
    b: &Bodies,
    cell: Option<&Cell>,
    cell_dist: &[i32; 3],
    shift2: &Vec3,
    id1: usize,
    id2: usize,
) -> law::viscel::Bodies {
    let (shift_vel, shift2) = shifts(cell, cell_dist, shift2);
    law::viscel::Bodies {
        pos1: b.pos[id1],
        pos2: b.pos[id2],
        vel1: b.vel[id1],
        vel2: b.vel[id2],
        ang_vel1: b.ang_vel[id1],
        ang_vel2: b.ang_vel[id2],
        shift2,
        shift_vel,
    }
}

/// Add a law's load (true: the contact stays), or report the erasure (false).
fn apply_or_erase(forces: &mut Forces, id1: usize, id2: usize, l: Option<law::Load>) -> bool {
    match l {
        Some(l) => {
            law::apply(forces, id1, id2, &l);
            true
        }
        None => false,
    }
}

fn cell_dist_of(intrs: &Interactions, k: usize) -> [i32; 3] {
    intrs.list[k].cell_dist
}

#[cfg(test)]
mod tests {
    use super::*;

    fn geom(il: &InteractionLoop, a: ShapeClass, b: ShapeClass) -> Option<(GeomFunctor, bool)> {
        dispatch::resolve(&il.geom_entries(), true, a, b, Some, Some).unwrap()
    }

    /// The dispatch facts of grid-pid-api.md 1.1/1.13: the grid shapes are Spheres for dispatch.
    #[test]
    fn grid_shapes_dispatch_through_the_sphere_hierarchy() {
        use ShapeClass::*;
        let mut il = InteractionLoop {
            gridnode_gridnode: Some(Default::default()),
            sphere_gridco: Some(1.0),
            gridco_gridco: true,
            ..InteractionLoop::default()
        };
        assert_eq!(
            geom(&il, GridConnection, Sphere),
            Some((GeomFunctor::SphereGridConnection, true))
        );
        assert_eq!(
            geom(&il, Sphere, GridConnection),
            Some((GeomFunctor::SphereGridConnection, false))
        );
        assert_eq!(
            geom(&il, GridNode, GridNode),
            Some((GeomFunctor::GridNodeGridNode, false))
        );
        // pitfall 2: a facet takes a connection for a sphere
        assert_eq!(
            geom(&il, Facet, GridConnection),
            Some((GeomFunctor::FacetSphere, false))
        );
        assert_eq!(
            geom(&il, GridConnection, Facet),
            Some((GeomFunctor::FacetSphere, true))
        );
        // pitfall 1: without the GC-GC functor, GC-GC pairs go to the sphere-connection one
        il.gridco_gridco = false;
        assert_eq!(
            geom(&il, GridConnection, GridConnection),
            Some((GeomFunctor::SphereGridConnection, false))
        );
        // without the sphere-connection functor, a sphere meets a connection as a sphere
        il.sphere_gridco = None;
        assert_eq!(
            geom(&il, Sphere, GridConnection),
            Some((GeomFunctor::SphereSphere, false))
        );
        assert_eq!(geom(&il, Wall, Box), None);
    }

    #[test]
    fn cpm_dispatch_declares_frictmat_first() {
        use MatClass::*;
        let mut il = InteractionLoop::empty();
        il.frict_phys = true;
        il.cpm_phys = Some(10);
        il.frict_cpm_phys = true;
        assert_eq!(
            il.phys_functor(CpmMat, CpmMat).unwrap(),
            Some((PhysFunctor::Cpm, false))
        );
        assert_eq!(
            il.phys_functor(FrictMat, CpmMat).unwrap(),
            Some((PhysFunctor::FrictCpm, false))
        );
        // YADE's dispatcher would swap the materials here (and Debian's YADE aborts on it)
        assert_eq!(
            il.phys_functor(CpmMat, FrictMat).unwrap(),
            Some((PhysFunctor::FrictCpm, true))
        );
        il.frict_cpm_phys = false;
        // without the mixed functor a CpmMat falls back to FrictMat
        assert_eq!(
            il.phys_functor(CpmMat, FrictMat).unwrap(),
            Some((PhysFunctor::Frict, false))
        );
    }

    #[test]
    fn physics_and_laws_fall_back_to_their_bases() {
        let il = InteractionLoop {
            cohfrict_phys: Some(Default::default()),
            cohesion_moment: Some(Default::default()),
            scgridco_frict: Some(Default::default()),
            ..InteractionLoop::default()
        };
        use MatClass::*;
        assert_eq!(
            il.phys_functor(CohFrictMat, CohFrictMat)
                .unwrap()
                .map(|(f, _)| f),
            Some(PhysFunctor::CohFrict)
        );
        assert_eq!(
            il.phys_functor(CohFrictMat, FrictMat)
                .unwrap()
                .map(|(f, _)| f),
            Some(PhysFunctor::Frict)
        );
        assert_eq!(
            il.phys_functor(FrictMat, CohFrictMat)
                .unwrap()
                .map(|(f, _)| f),
            Some(PhysFunctor::Frict)
        );
        use GeomClass as G;
        use PhysClass as P;
        assert_eq!(
            il.law_functor(G::GridNodeGeom6D, P::CohFrictPhys).unwrap(),
            Some(LawFunctor::CohesionMoment)
        );
        assert_eq!(
            il.law_functor(G::ScGeom6D, P::FrictPhys).unwrap(),
            Some(LawFunctor::CundallStrack)
        );
        assert_eq!(
            il.law_functor(G::ScGeom, P::CohFrictPhys).unwrap(),
            Some(LawFunctor::CundallStrack)
        );
        assert_eq!(
            il.law_functor(G::ScGridCoGeom, P::FrictPhys).unwrap(),
            Some(LawFunctor::ScGridCoFrict)
        );
        // a cohesive sphere-connection contact without its own law: the 6-D cohesive law is nearer
        assert_eq!(
            il.law_functor(G::ScGridCoGeom, P::CohFrictPhys).unwrap(),
            Some(LawFunctor::CohesionMoment)
        );
        let bare = InteractionLoop::empty();
        assert_eq!(bare.law_functor(G::ScGeom, P::FrictPhys).unwrap(), None);
        // the shortcut cells answer as the whole table does, whatever laws are registered
        let gs = [
            G::IGeom,
            G::GenericSpheresContact,
            G::ScGeom,
            G::ScGeom6D,
            G::GridNodeGeom6D,
            G::ScGridCoGeom,
            G::GridCoGridCoGeom,
        ];
        let ps = [
            P::IPhys,
            P::NormPhys,
            P::NormShearPhys,
            P::FrictPhys,
            P::RotStiffFrictPhys,
            P::CohFrictPhys,
            P::ViscElPhys,
            P::MindlinPhys,
            P::LudingPhys,
            P::BubblePhys,
            P::CpmPhys,
        ];
        let ms = [
            MatClass::Material,
            MatClass::ElastMat,
            FrictMat,
            CohFrictMat,
            ViscElMat,
            MatClass::LudingMat,
            MatClass::BubbleMat,
            MatClass::CpmMat,
        ];
        let mut phys_hits = 0;
        for bits in 0..256u32 {
            let on = |i: u32| bits & (1 << i) != 0;
            let l = InteractionLoop {
                frict_phys: on(0),
                cohfrict_phys: on(1).then(Default::default),
                viscel_phys: on(2),
                luding_phys: on(3),
                bubble_phys: on(4),
                mindlin_phys: on(5).then(Default::default),
                cpm_phys: on(6).then_some(10),
                frict_cpm_phys: on(7),
                ..InteractionLoop::empty()
            };
            for a in ms {
                for b in ms {
                    // (an ambiguous dispatch is an error in both)
                    let fast = l.phys_functor(a, b).ok();
                    assert_eq!(
                        fast,
                        l.phys_functor_table(a, b).ok(),
                        "{bits:b} {a:?} {b:?}"
                    );
                    phys_hits += fast.flatten().is_some() as usize;
                }
            }
        }
        assert!(phys_hits > 1000, "{phys_hits}");
        let mut shortcut_hits = 0;
        for bits in 0..1024u32 {
            let on = |i: u32| bits & (1 << i) != 0;
            let l = InteractionLoop {
                cundall_strack: on(0).then(|| il.cundall_strack.unwrap()),
                cohesion_moment: on(1).then(|| il.cohesion_moment.unwrap()),
                scgridco_frict: on(2).then(|| il.scgridco_frict.unwrap()),
                scgridco_cohfrict: on(3).then(Default::default),
                gridco_gridco_frict: on(4).then(Default::default),
                viscel_basic: on(5),
                mindlin: on(6).then(Default::default),
                luding_basic: on(7),
                bubble: on(8).then(Default::default),
                cpm: on(9).then(Default::default),
                ..InteractionLoop::empty()
            };
            for g in gs {
                for p in ps {
                    // (an ambiguous dispatch is an error in both)
                    let fast = l.law_functor(g, p).ok();
                    assert_eq!(fast, l.law_functor_table(g, p).ok(), "{bits:b} {g:?} {p:?}");
                    shortcut_hits += fast.flatten().is_some() as usize;
                }
            }
        }
        assert!(shortcut_hits > 3000, "{shortcut_hits}");
        // ViscElMat is a FrictMat: a ViscElMat pair gets its own Ip2 only when given, a mixed pair
        // the FrictMat one; a ViscElPhys without its law falls back to Cundall-Strack (a FrictPhys)
        let ve = InteractionLoop {
            viscel_phys: true,
            viscel_basic: true,
            ..InteractionLoop::default()
        };
        assert_eq!(
            ve.phys_functor(ViscElMat, ViscElMat)
                .unwrap()
                .map(|(f, _)| f),
            Some(PhysFunctor::ViscEl)
        );
        assert_eq!(
            ve.phys_functor(ViscElMat, FrictMat)
                .unwrap()
                .map(|(f, _)| f),
            Some(PhysFunctor::Frict)
        );
        assert_eq!(
            il.phys_functor(ViscElMat, ViscElMat)
                .unwrap()
                .map(|(f, _)| f),
            Some(PhysFunctor::Frict)
        );
        assert_eq!(
            ve.law_functor(G::ScGeom, P::ViscElPhys).unwrap(),
            Some(LawFunctor::ViscElBasic)
        );
        assert_eq!(
            il.law_functor(G::ScGeom, P::ViscElPhys).unwrap(),
            Some(LawFunctor::CundallStrack)
        );
    }
}
