# The geogrid study (/work/shared/study.md, paper: /work/shared/seed-paper.txt) as ONE plain YADE script.
#
#   yade -n -x yade_ref/study/study.py -- --ratio 0.5 --case G --size tiny --seed 1 --out /tmp/r05_G
#   ./target/release/compat run yade_ref/study/study.py -- <same arguments>      (ryade)
#
# A layer of mono-sized spheres on a fixed plate in a periodic cell (x, y), optionally with a
# periodic triaxial geogrid (case G) or with the mid-layer spheres blocked in x, y (case F), is
# generated (two makeCloud clouds, deposition, 3 oedometric load/unload cycles with a huge top plate,
# lift-and-park, settle) and then loaded by a 24-segment facet piston: approach, seating at 27.6 kPa
# for one period, then haversine cycles 27.6 -> 275.8 kPa at 50 Hz under a filtered PI velocity
# controller (or YADE's ServoPIDController with --controller servopid). Per cycle it records the rut,
# the peak pressure, the tracking error and the porosity of the box under the piston.
#
# Outputs in --out (README.md next to this file has the columns and units):
#   history.csv  one row per cycle (cycle 0 = end of seating)
#   steps.csv    piston pressure / target / position every --steps-every steps of the loading
#   profile.csv  final vertical displacement by depth, under the piston footprint and outside it
#   summary.json parameters, derived values, generation results, timings per phase
#   specimen.json (with --export-specimen FILE: FILE) the specimen after generation
#
# The specimen is handed from generation to loading through its JSON form: after generation the
# scene is rebuilt from the exported body data (O.reset(), same ids, same doubles), exactly as
# --import-specimen does, so a run that generates and a run that imports the specimen load the
# same scene step for step (contacts are re-detected at the rebuild: shear forces start at zero,
# grid bonds are re-created stress-free at the imported node positions). --no-rebuild skips this.
#
# Unmodelled-effect knobs (issue 7; README "Unmodelled-effect knobs"), all off by default: --psd-fuzz
# (generation), --eta-roll/--alpha-kr/--roll-plates, --subgrade-k/--subgrade-mass/--subgrade-zeta,
# --grid-kn-scale/--grid-kr-scale, --load-friction (loading, applied at the specimen rebuild).
#
# Only common YADE API is used (O.bodies, utils.sphere/box, pack.SpherePack.makeCloud, geom.facetCylinder,
# PyRunner, O.forces.f); yade.gridpfacet only in case G.
import argparse, json, math, os, sys, time

from yade import pack, geom, utils

# ----------------------------------------------------------------------------------------------
# parameters

SIZES = {  # nx x ny rectangular lattice periods, piston diameter [m], default cycles
    'tiny': (3, 2, 0.09, 5),
    'small': (4, 2, 0.10, 10),
    'medium': (5, 3, 0.15, 10),
    'full': (10, 6, 0.30, 10),
}


# parameters an imported specimen fixes (the others come from the command line)
SPECIMEN_PARAMS = ('ratio', 'case', 'size', 'seed', 'rib', 'nx', 'ny', 'young', 'poisson', 'friction', 'density',
                   'grid_young', 'grid_poisson', 'grid_density', 'grid_radius', 'mid_rib', 'layer', 'target_porosity',
                   'cloud_fraction', 'oedo_kpa', 'oedo_cycles', 'settle_tol', 'freq', 'psd_fuzz', 'clump_size')


# unmodelled-effect knobs (README "Unmodelled-effect knobs"): at these values the model is exactly the
# study's. They are written to specimen.json / summary.json only when they differ, so default runs
# write the same files as before the knobs existed. Only psd_fuzz changes the generation (it is a
# SPECIMEN_PARAM; specimens written before it existed read as 0); the others act on the loading.
KNOB_DEFAULTS = {'psd_fuzz': 0.0, 'clump_size': 0, 'eta_roll': 0.0, 'alpha_kr': 2.0, 'roll_plates': False, 'subgrade_k': 0.0,
                 'subgrade_mass': None, 'subgrade_zeta': 0.2, 'grid_kn_scale': 1.0, 'grid_kr_scale': 1.0, 'load_friction': None,
                 'grid_block': '', 'block_rotations': False, 'preset': None, 'profile_cycle': 0, 'adapt_gains': 0.0}


# named presets (README "Preset paper200"): defaults for a group of options, chosen per ratio d/a where the
# specimen preparation needs it; an option given on the command line overrides its preset value.
PRESETS = {
    'paper200': {
        # loading: rolling resistance as the angularity proxy the paper names, crushed-aggregate friction
        # (steps.csv every 50 steps: 18 samples a cycle, 3,640 rows for 200 cycles)
        # (PI gains: stiffness factor 0.075; at 0.05 the filtered peak overshot to 317 kPa at r07 full, at 0.1 the
        # tracking error at medium size doubled: results/paper200/sweep.md "Controller")
        'all': {'cycles': 200, 'eta_roll': 0.5, 'load_friction': 35.0, 'steps_every': 50, 'profile_cycle': 100,
                'stiffness_factor': 0.075, 'adapt_gains': 0.08},
        # generation: compaction friction (lower = denser) and the porosity that sets the sphere count, so that
        # N and G land at 25 +- 1 cm and 41-46 % porosity (measured, seed 1, in the README's preset table)
        0.3: {'friction': 25.0, 'target_porosity': 0.415},
        0.5: {'friction': 10.0, 'target_porosity': 0.42},
        0.7: {'friction': 10.0, 'target_porosity': 0.437},
    },
}


def preset_values(name, ratio):
    """The option defaults of preset `name` for ratio d/a (the ratio's own entry, or the nearest one's)."""
    p = PRESETS[name]
    ratios = [k for k in p if k != 'all']
    near = min(ratios, key=lambda k: abs(k - ratio))
    v = dict(p['all'])
    v.update(p[near])
    return v


def params_dict(a, leave_out=()):
    return {k: v for k, v in sorted(vars(a).items()) if k not in leave_out and not (k in KNOB_DEFAULTS and v == KNOB_DEFAULTS[k])}


# run options that are not properties of the specimen (left out of specimen.json)
RUN_OPTIONS = ('out', 'export_specimen', 'import_specimen', 'generate_only', 'no_rebuild')


def parse_args(argv):
    if argv and argv[0] == '--':  # yade strips the '--', other launchers may not
        argv = argv[1:]
    ap = argparse.ArgumentParser(prog='study.py', description='The geogrid study (study.md) in YADE: generate a specimen and load it '
                                 'cyclically with a piston. See yade_ref/study/README.md.')
    ap.add_argument('--ratio', type=float, default=0.5, help='d/a: 0.3, 0.5 or 0.7 (sphere diameter d = ratio * 0.06 m)')
    ap.add_argument('--case', choices=['N', 'G', 'F'], default='N', help='N non-stabilized, G geogrid, F full lateral confinement')
    ap.add_argument('--size', choices=sorted(SIZES), default='tiny')
    ap.add_argument('--seed', type=int, default=1, help='makeCloud seed (>= 0); the upper cloud uses seed + 100000')
    ap.add_argument('--cycles', type=int, default=None, help='load cycles (default: tiny 5, small/medium/full 10)')
    ap.add_argument('--controller', choices=['pi', 'servopid', 'native'], default='pi',
                    help="pi: the study's filtered PI velocity law in a PyRunner (default); servopid: YADE's ServoPIDController on the raw force, same gains; "
                    "native: the pi law run by ryade's RyadePistonController engine, no Python call per step (ryade only, same outputs; YADE runs the PyRunner law)")
    ap.add_argument('--out', default=None, help='output directory (default: study_out/r<ratio>_<case>_<size>_s<seed>)')
    ap.add_argument('--export-specimen', default=None, metavar='FILE', help='write the specimen after generation as JSON')
    ap.add_argument('--import-specimen', default=None, metavar='FILE', help='skip generation, rebuild this specimen and load it')
    ap.add_argument('--generate-only', action='store_true', help='stop after generation (and the export)')
    ap.add_argument('--no-rebuild', action='store_true', help='load the generated scene as is (keeps contact history; not reproducible by --import-specimen)')
    # geometry / materials (study.md defaults)
    ap.add_argument('--rib', type=float, default=0.06, help='rib length a [m]')
    ap.add_argument('--nx', type=int, default=None, help='override the lattice periods along x')
    ap.add_argument('--ny', type=int, default=None, help='override the rectangular lattice periods along y')
    ap.add_argument('--piston-d', type=float, default=None, help='piston diameter [m] (default per size, D/Lx = 0.5)')
    ap.add_argument('--young', type=float, default=1e8)
    ap.add_argument('--poisson', type=float, default=0.25)
    ap.add_argument('--friction', type=float, default=30.0, help='sphere/plate/piston/rib friction angle [deg]')
    ap.add_argument('--density', type=float, default=2650.0)
    ap.add_argument('--damping', type=float, default=0.2, help='NewtonIntegrator local damping (every phase)')
    ap.add_argument('--grid-young', type=float, default=1e9)
    ap.add_argument('--grid-poisson', type=float, default=0.3)
    ap.add_argument('--grid-density', type=float, default=950.0)
    ap.add_argument('--grid-radius', type=float, default=0.002)
    ap.add_argument('--mid-rib', action='store_true', help="paper's ribs: an articulated node at every rib's mid-length")
    ap.add_argument('--layer', type=float, default=0.25, help='target layer thickness [m] (sets the sphere count)')
    ap.add_argument('--target-porosity', type=float, default=0.43)
    ap.add_argument('--cloud-fraction', type=float, default=0.22, help='solid fraction of the makeCloud boxes')
    # generation
    ap.add_argument('--oedo-kpa', type=float, default=300.0, help='oedometric load at which the top plate reverses [kPa]')
    ap.add_argument('--oedo-cycles', type=int, default=3)
    ap.add_argument('--settle-tol', type=float, default=0.02, help='unbalancedForce threshold of the final settling')
    # loading
    ap.add_argument('--seat-kpa', type=float, default=27.6)
    ap.add_argument('--peak-kpa', type=float, default=275.8)
    ap.add_argument('--freq', type=float, default=50.0)
    ap.add_argument('--wave', choices=['haversine', 'triangle'], default='haversine')
    ap.add_argument('--stiffness-factor', type=float, default=0.05, help='K = factor * 2E/(pi D/2): rigid-punch stiffness guess for the PI gains')
    ap.add_argument('--vmax', type=float, default=1.0, help='piston speed limit [m/s]')
    ap.add_argument('--stop-rut', type=float, default=0.075, help='stop when the rut exceeds this [m] (0.3 x 0.25 m)')
    ap.add_argument('--steps-every', type=int, default=10, help='steps.csv sampling period [steps]')
    ap.add_argument('--adapt-gains', type=float, default=0.0, metavar='X',
                    help='after a cycle whose filtered peak misses the target by more than the fraction X, scale the PI gains by 1.1 '
                         '(short) or 1/1.1 (over), within [0.5, 4] x the initial ones (0: fixed gains; not with --controller servopid)')
    ap.add_argument('--profile-cycle', type=int, default=0, metavar='K',
                    help='also write profile_cK.csv: the displacement profile at the end of cycle K (0: only the final profile.csv)')
    # unmodelled-effect knobs (README "Unmodelled-effect knobs"); the defaults are the study's model
    ap.add_argument('--psd-fuzz', type=float, default=0.0,
                    help='generation: makeCloud rRelFuzz (radii uniform in r(1 +- fuzz), same mean radius, count from the mean volume)')
    ap.add_argument('--eta-roll', type=float, default=0.0,
                    help='loading: rolling resistance of sphere-sphere contacts (CohFrictMat etaRoll, CohesionMoment law); 0 = none')
    ap.add_argument('--alpha-kr', type=float, default=2.0, help='loading: CohFrictMat alphaKr of the rolling spheres (with --eta-roll)')
    ap.add_argument('--roll-plates', action='store_true',
                    help='with --eta-roll: plates and piston roll-resist too (Ig2_Box/Facet_Sphere_ScGeom6D; YADE only, not in ryade)')
    ap.add_argument('--subgrade-k', type=float, default=0.0,
                    help='loading: modulus of subgrade reaction [N/m^3] under the bottom plate (Winkler spring bed); 0 = rigid, fixed plate')
    ap.add_argument('--subgrade-mass', type=float, default=None, help='plate mass [kg] with --subgrade-k (default 0.1 x the layer mass)')
    ap.add_argument('--subgrade-zeta', type=float, default=0.2, help='spring-bed dashpot as a fraction of the plate-alone critical damping')
    ap.add_argument('--grid-kn-scale', type=float, default=1.0, help='loading: multiply kn and ks of every grid bond')
    ap.add_argument('--grid-kr-scale', type=float, default=1.0, help='loading: multiply kr and ktw of every grid bond')
    ap.add_argument('--clump-size', type=int, default=0, choices=[0, 2, 3, 4],
                    help='generation: replace every sphere by a clump of K overlapping spheres of the same total volume (0: spheres)')
    ap.add_argument('--load-friction', type=float, default=None,
                    help='loading: friction angle [deg] of the grain and rib materials from the rebuild on (default: the specimen\'s --friction)')
    ap.add_argument('--grid-block', default='', metavar='DOFS',
                    help="loading, diagnostic: blockedDOFs of every grid node (e.g. 'z', 'xyz', 'XYZ'): what if the grid could not move")
    ap.add_argument('--block-rotations', action='store_true',
                    help='loading: block the rotations of every sphere (XYZ added to blockedDOFs; the limit of infinite rolling resistance)')
    ap.add_argument('--preset', choices=sorted(PRESETS), default=None,
                    help='named defaults for a group of options (README "Preset paper200"); explicit options override them')
    first, _ = ap.parse_known_args(argv)
    if first.preset:
        ratio = first.ratio
        if first.import_specimen:
            with open(first.import_specimen) as f:
                ratio = json.load(f)['params']['ratio']
        ap.set_defaults(**preset_values(first.preset, ratio))
    a = ap.parse_args(argv)
    if a.import_specimen:  # the specimen fixes the geometry and the materials
        with open(a.import_specimen) as f:
            a.specimen = json.load(f)
        sp = a.specimen['params']
        fixed = {k: sp.get(k, KNOB_DEFAULTS.get(k)) if k in KNOB_DEFAULTS else sp[k] for k in SPECIMEN_PARAMS}
        # a specimen parameter asked for on the command line that the imported specimen contradicts
        clash = ['--%s %s (the specimen has %s)' % (k.replace('_', '-'), getattr(a, k), fixed[k]) for k in SPECIMEN_PARAMS
                 if getattr(a, k, None) is not None and getattr(a, k) != ap.get_default(k) and getattr(a, k) != fixed[k]]
        if clash:
            ap.error('--import-specimen fixes the generation and the materials; these options would be ignored: %s. '
                     'Leave them out, or generate a specimen with them (the loading has its own knobs, e.g. --load-friction)'
                     % ', '.join(clash))
        for k in SPECIMEN_PARAMS:
            setattr(a, k, fixed[k])
        if a.piston_d is None:
            a.piston_d = sp['piston_d']
    nx, ny, D, cyc = SIZES[a.size]
    a.nx = a.nx or nx
    a.ny = a.ny or ny
    a.piston_d = a.piston_d or D
    if a.cycles is None:
        a.cycles = cyc
    if a.seed < 0:
        ap.error('--seed must be >= 0 (makeCloud with seed < 0 is not reproducible)')
    if a.nx < 3 or a.ny < 2:
        ap.error('a periodic triaxial grid needs nx >= 3 and ny >= 2')
    if not 0 <= a.psd_fuzz < 1:
        ap.error('--psd-fuzz must be in [0, 1)')
    if a.no_rebuild and any(getattr(a, k) != v for k, v in KNOB_DEFAULTS.items() if k not in ('psd_fuzz', 'clump_size')):
        ap.error('the loading knobs act at the specimen rebuild: not with --no-rebuild')
    if a.adapt_gains and a.controller == 'servopid':
        ap.error('--adapt-gains scales the PI law of --controller pi/native, not ServoPIDController')
    if a.roll_plates and not a.eta_roll > 0:
        ap.error('--roll-plates needs --eta-roll > 0')
    if a.out is None:
        a.out = os.path.join('study_out', 'r%02d_%s_%s_s%d' % (round(a.ratio * 10), a.case, a.size, a.seed))
    return a


class Params:
    """Derived quantities (study.md "Scenario definition")."""

    def __init__(self, a):
        self.a = a
        self.rib = a.rib
        self.d = a.ratio * a.rib
        self.r = self.d / 2
        self.rMin = self.r * (1 - a.psd_fuzz)  # with --psd-fuzz the radii are uniform in [rMin, rMax]
        self.rMax = self.r * (1 + a.psd_fuzz)
        self.rg = a.grid_radius
        self.Lx = a.nx * a.rib
        self.Ly = a.ny * a.rib * math.sqrt(3)
        self.Z0 = 0.05
        self.D = a.piston_d
        self.A = math.pi * self.D**2 / 4
        self.cx, self.cy = self.Lx / 2, self.Ly / 2
        vs = math.pi * self.d**3 / 6 * (1 + a.psd_fuzz**2)  # E[r^3] = r^3 (1 + fuzz^2) for uniform radii
        self.nSpheres = int(round((1 - a.target_porosity) * self.Lx * self.Ly * a.layer / vs))
        self.H0 = a.layer * (1 - a.target_porosity) / a.cloud_fraction  # height of the two clouds together
        # clouds: lower box, an empty slab around the grid plane, upper box
        self.gapHalf = self.rMax + self.rg + 0.1 * self.rMax
        self.zLow0 = self.Z0 + 1.05 * self.rMax
        self.zLow1 = self.zLow0 + 0.5 * self.H0
        self.zGrid = self.zLow1 + self.gapHalf
        self.zUp0 = self.zGrid + self.gapHalf
        self.zUp1 = self.zUp0 + 0.5 * self.H0
        self.Lz = self.zUp1 + 4 * self.d + 0.3
        # time step (study.md pitfall 5): sphere limit and the grid-node limit, for every case,
        # rounded down to an integer number of steps per load period
        self.T = 1.0 / a.freq
        ribL = self.rib / 2 if a.mid_rib else self.rib
        nRibs = 2 if a.mid_rib else 6  # the lightest node: a mid-rib node (2 half ribs) or a junction (6)
        self.mNode = nRibs * 0.5 * ribL * math.pi * self.rg**2 * a.grid_density
        dtSph = 0.5 * self.rMin * math.sqrt(a.density / a.young)
        dtGrid = 0.3 * math.sqrt(self.mNode / (2 * a.young * self.rg))
        self.dt0 = min(dtSph, dtGrid)
        self.stepsPerCycle = int(math.ceil(self.T / self.dt0))
        self.dt = self.T / self.stepsPerCycle
        # PI gains (study.md loading protocol 3)
        self.K = a.stiffness_factor * 2 * a.young / (math.pi * self.D / 2)
        self.tau = 0.1 * self.T
        self.Kp = 1.0 / (self.K * self.tau)
        self.Ki = self.Kp / (0.5 * self.T)
        self.alpha = self.dt / (0.01 * self.T + self.dt)


# ----------------------------------------------------------------------------------------------
# exact sphere / box intersection volume (study.md loading protocol 4): the disc-rectangle area in
# closed form, integrated over z = zc + r sin(theta) with 24-point Gauss-Legendre in theta.


def gauss_legendre(n):
    xs, ws = [], []
    for i in range(1, n + 1):
        x = math.cos(math.pi * (i - 0.25) / (n + 0.5))
        for _ in range(100):
            p0, p1 = 1.0, x
            for k in range(2, n + 1):
                p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
            dp = n * (x * p1 - p0) / (x * x - 1)
            dx = p1 / dp
            x -= dx
            if abs(dx) < 1e-16:
                break
        xs.append(x)
        ws.append(2 / ((1 - x * x) * dp * dp))
    return xs, ws


GL_X, GL_W = gauss_legendre(24)


def _segment(b, rho):
    """Area of the disc (radius rho, centre 0) in y >= b."""
    if b >= rho:
        return 0.0
    if b <= -rho:
        return math.pi * rho * rho
    return rho * rho * math.acos(b / rho) - b * math.sqrt(rho * rho - b * b)


def _quadrant(a, b, rho):
    """Area of the disc (radius rho, centre 0) in x >= a, y >= b, any signs."""
    if a < 0:
        return _segment(b, rho) - _quadrant(-a, b, rho)
    if b < 0:
        return _segment(a, rho) - _quadrant(a, -b, rho)
    if a * a + b * b >= rho * rho:
        return 0.0
    return (0.5 * rho * rho * (0.5 * math.pi - math.asin(a / rho) - math.asin(b / rho))
            - 0.5 * (a * math.sqrt(rho * rho - a * a) + b * math.sqrt(rho * rho - b * b)) + a * b)


def disc_rect_area(rho, x0, x1, y0, y1):
    """Area of the disc (radius rho, centre 0) inside [x0, x1] x [y0, y1]."""
    return (_quadrant(x0, y0, rho) - _quadrant(x1, y0, rho) - _quadrant(x0, y1, rho) + _quadrant(x1, y1, rho))


def sphere_box_volume(c, r, lo, hi):
    x0, x1 = lo[0] - c[0], hi[0] - c[0]
    y0, y1 = lo[1] - c[1], hi[1] - c[1]
    z0, z1 = lo[2] - c[2], hi[2] - c[2]
    if x0 >= r or x1 <= -r or y0 >= r or y1 <= -r or z0 >= r or z1 <= -r:
        return 0.0
    if x0 <= -r and x1 >= r and y0 <= -r and y1 >= r and z0 <= -r and z1 >= r:
        return 4.0 / 3.0 * math.pi * r**3
    t0 = math.asin(max(-1.0, z0 / r))
    t1 = math.asin(min(1.0, z1 / r))
    inXY = x0 <= -r and x1 >= r and y0 <= -r and y1 >= r
    h, m = 0.5 * (t1 - t0), 0.5 * (t1 + t0)
    v = 0.0
    for x, w in zip(GL_X, GL_W):
        t = m + h * x
        rho = r * math.cos(t)
        area = math.pi * rho * rho if inXY else disc_rect_area(rho, x0, x1, y0, y1)
        v += w * area * rho
    return v * h


def box_porosity(spheres, lo, hi, Lx, Ly):
    """1 - V_solid / V_box for the box [lo, hi]; spheres = [(pos, r)], periodic images in x, y."""
    vol = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2])
    solid = 0.0
    for c, r in spheres:
        if c[2] + r <= lo[2] or c[2] - r >= hi[2]:
            continue
        for i in range(int(math.ceil((lo[0] - r - c[0]) / Lx)), int(math.floor((hi[0] + r - c[0]) / Lx)) + 1):
            for j in range(int(math.ceil((lo[1] - r - c[1]) / Ly)), int(math.floor((hi[1] + r - c[1]) / Ly)) + 1):
                solid += sphere_box_volume((c[0] + i * Lx, c[1] + j * Ly, c[2]), r, lo, hi)
    return 1.0 - solid / vol


# ----------------------------------------------------------------------------------------------
# scene


def stop_after_this_step():
    """End the current O.run() after this step, from a PyRunner. Not O.pause(): under yade the main
    thread's O.wait() can return while the worker thread is still finishing the step (O.iter not yet
    incremented), so what the script does next would race with it. stopAtIter ends the run only after
    the step is complete. The caller resets O.stopAtIter = 0 after the run."""
    O.stopAtIter = O.iter + 1


def run_until_stopped(cap):
    """O.run(cap, True) that a PyRunner may end earlier with stop_after_this_step()."""
    O.run(cap, True)
    O.stopAtIter = 0


class Study:
    def __init__(self, a, P):
        self.a, self.P = a, P
        self.phase = 'idle'
        self.timings = []  # (phase, steps, wall seconds)
        self.info = {}
        self.spheres = []
        self.top = None
        self.piston = []
        self.gridNodes = []
        self.pc = None  # the native piston engine (--controller native under ryade)
        self.sub = None  # knob --subgrade-k: the spring-bed state, set by load()

    # --- engines, materials -------------------------------------------------------------------
    def setup_scene(self, loading=False):
        """Engines. loading=True (the rebuild): with --eta-roll the sphere-sphere geometry is ScGeom6D and
        the CohFrictMat contacts go through the CohesionMoment law (README "Unmodelled-effect knobs")."""
        a, P = self.a, self.P
        O.periodic = True
        O.cell.setBox(P.Lx, P.Ly, P.Lz)
        grid = a.case == 'G'
        roll = loading and a.eta_roll > 0
        bo1 = [Bo1_Sphere_Aabb(), Bo1_Box_Aabb(), Bo1_Facet_Aabb()]
        ig2 = [Ig2_Sphere_Sphere_ScGeom6D() if roll else Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()]
        if roll and a.roll_plates:  # YADE only: ryade has no Box/Facet-Sphere ScGeom6D
            ig2[1:] = [Ig2_Box_Sphere_ScGeom6D(), Ig2_Facet_Sphere_ScGeom6D()]
        ip2 = [Ip2_FrictMat_FrictMat_FrictPhys()]
        law2 = [Law2_ScGeom_FrictPhys_CundallStrack()]
        if grid or roll:
            # always_use_moment_law: non-cohesive contacts start with cohesionBroken=True;
            # useIncrementalForm: the etaRoll limit is then irreversible (rolling plasticity). With G this
            # functor also carries the grid bonds, so --eta-roll switches them to the incremental form too.
            ip2 = [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=grid, setCohesionOnNewContacts=False)] + ip2
            law2 += [Law2_ScGeom6D_CohFrictPhys_CohesionMoment(always_use_moment_law=True, useIncrementalForm=True) if roll
                     else Law2_ScGeom6D_CohFrictPhys_CohesionMoment()]
        if grid:
            bo1 += [Bo1_GridConnection_Aabb()]
            ig2 += [Ig2_GridNode_GridNode_GridNodeGeom6D(), Ig2_Sphere_GridConnection_ScGridCoGeom()]
            law2 += [Law2_ScGridCoGeom_FrictPhys_CundallStrack()]
        # allowBiggerThanPeriod: the plates are 100 m wide (pitfall 1). sortAxis=2: the initial sweep
        # runs along z, where the plates are thin, so every sphere resting on a plate when the
        # collider (re)initialises gets its pair (the x sweep misses some of them).
        collider = InsertionSortCollider(bo1, allowBiggerThanPeriod=True, sortAxis=2)
        if grid:
            collider.avoidSelfInteractionMask = 4  # ribs (mask 6) never pair with ribs
        engines = [
            ForceResetter(),
            collider,
            InteractionLoop(ig2, ip2, law2),
            NewtonIntegrator(damping=a.damping, gravity=(0, 0, -9.81)),
            PyRunner(command='study.tick()', iterPeriod=1, label='ctl'),
        ]
        if a.controller == 'servopid':
            engines.append(ServoPIDController(ids=[], axis=(0, 0, 1), target=0, kP=P.Kp / P.A, kI=P.Ki * P.dt / P.A, kD=0,
                                              maxVelocity=a.vmax, iterPeriod=1, dead=True, label='servo'))
        O.engines = engines
        O.dt = P.dt

    def add_materials(self):
        a = self.a
        fr = math.radians(a.friction)
        self.matGrain = O.materials.append(FrictMat(young=a.young, poisson=a.poisson, frictionAngle=fr, density=a.density, label='grain'))
        self.matRib = self.matNode = None
        if a.case == 'G':
            self.matRib = O.materials.append(FrictMat(young=a.young, poisson=a.poisson, frictionAngle=fr, density=a.grid_density, label='rib'))
            self.matNode = O.materials.append(CohFrictMat(young=a.grid_young, poisson=a.grid_poisson, density=a.grid_density,
                                                          normalCohesion=1e100, shearCohesion=1e100, momentRotationLaw=True, label='node'))

    # --- generation ---------------------------------------------------------------------------
    def timed(self, name, fn):
        it0, t0, c0 = O.iter, time.time(), time.process_time()
        res = fn()
        n = max(0, O.iter - it0)  # O.reset() (rebuild) sets O.iter back to 0
        self.timings.append((name, n, time.time() - t0, time.process_time() - c0))
        print('[study] %-12s %7d steps %8.2f s wall %8.2f s cpu' % (name, n, time.time() - t0, time.process_time() - c0), flush=True)
        return res

    def make_clouds(self):
        a, P = self.a, self.P
        O.bodies.append(utils.box((P.cx, P.cy, P.Z0 - 0.01), (50, 50, 0.01), fixed=True, material=self.matGrain, mask=1))
        nLow = P.nSpheres // 2
        for (z0, z1, n, seed) in [(P.zLow0, P.zLow1, nLow, a.seed), (P.zUp0, P.zUp1, P.nSpheres - nLow, a.seed + 100000)]:
            sp = pack.SpherePack()
            got = sp.makeCloud((0, 0, z0), (P.Lx, P.Ly, z1), rMean=P.r, rRelFuzz=a.psd_fuzz, num=n, periodic=True, seed=seed)
            if got != n:
                raise RuntimeError('makeCloud placed %d of %d spheres (cloud too dense)' % (got, n))
            if a.clump_size:
                self.make_clumps(sp, seed)
                continue
            for c, rad in sp:
                self.spheres.append(O.bodies.append(utils.sphere(c, rad, material=self.matGrain, mask=3)))
        if a.case == 'G':
            self.make_grid(P.zGrid)

    # regular unit directions of K members: a pair, an equilateral triangle, a regular tetrahedron
    CLUMP_DIRS = {2: [(1.0, 0.0, 0.0), (-1.0, 0.0, 0.0)],
                  3: [(1.0, 0.0, 0.0), (-0.5, math.sqrt(3) / 2, 0.0), (-0.5, -math.sqrt(3) / 2, 0.0)],
                  4: [(s3 * x, s3 * y, s3 * z) for s3 in (1 / math.sqrt(3),)
                      for (x, y, z) in ((1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1))]}

    def make_clumps(self, sp, seed):
        """Knob --clump-size K: each cloud sphere (centre c, radius R) becomes a clump of K equal spheres of
        radius R/K^(1/3) (the same total volume, overlaps counted twice as YADE's clump mass does) whose
        centres sit at distance R - R/K^(1/3) from c along K regular directions turned by a random
        rotation, so that the clump stays inside the original sphere (makeCloud's non-overlap holds).
        The rotations come from Python's Mersenne Twister seeded with the cloud seed: the same in YADE
        and ryade. self.spheres lists the member spheres; O.bodies.appendClumped (discretization 0)."""
        import random
        K = self.a.clump_size
        rng = random.Random(seed)
        dirs = self.CLUMP_DIRS[K]
        for c, rad in sp:
            rm = rad / K ** (1.0 / 3.0)
            off = rad - rm
            # uniform random rotation (Shoemake) as a matrix
            u1, u2, u3 = rng.random(), rng.random(), rng.random()
            qx, qy = math.sqrt(1 - u1) * math.sin(2 * math.pi * u2), math.sqrt(1 - u1) * math.cos(2 * math.pi * u2)
            qz, qw = math.sqrt(u1) * math.sin(2 * math.pi * u3), math.sqrt(u1) * math.cos(2 * math.pi * u3)
            R = ((1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)),
                 (2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)),
                 (2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)))
            members = []
            for d in dirs:
                e = [R[i][0] * d[0] + R[i][1] * d[1] + R[i][2] * d[2] for i in range(3)]
                members.append(utils.sphere((c[0] + off * e[0], c[1] + off * e[1], c[2] + off * e[2]), rm,
                                            material=self.matGrain, mask=3))
            cid, ids = O.bodies.appendClumped(members)
            self.spheres.extend(ids)

    def grid_layout(self, z):
        """Junctions (row j, column i) and ribs (node1, node2, cellDist), as study.md "Geogrid"."""
        a, P = self.a, self.P
        nx, rows = a.nx, 2 * a.ny
        pitch = P.rib * math.sqrt(3) / 2
        nodes = [((i + 0.25 + 0.5 * (j % 2)) * P.rib, (j + 0.5) * pitch, z) for j in range(rows) for i in range(nx)]
        ribs = []
        for j in range(rows):
            for i in range(nx):
                ribs.append((j * nx + i, j * nx + (i + 1) % nx, ((i + 1) // nx, 0, 0)))
                jn, cy = (j + 1) % rows, (j + 1) // rows
                for inb in ((i - 1, i) if j % 2 == 0 else (i, i + 1)):
                    ribs.append((j * nx + i, jn * nx + inb % nx, (inb // nx, cy, 0)))
        if a.mid_rib:
            split = []
            for (n1, n2, cd) in ribs:
                p1, p2 = nodes[n1], nodes[n2]
                nodes.append(tuple(0.5 * (p1[k] + p2[k] + (cd[k] * (P.Lx if k == 0 else P.Ly) if k < 2 else 0)) for k in range(3)))
                split += [(n1, len(nodes) - 1, (0, 0, 0)), (len(nodes) - 1, n2, cd)]
            ribs = split
        return nodes, ribs

    def make_grid(self, z):
        from yade.gridpfacet import gridNode, gridConnection
        from yade.minieigenHP import Vector3i
        nodes, ribs = self.grid_layout(z)
        ids = [O.bodies.append(gridNode(p, self.P.rg, fixed=False, material=self.matNode)) for p in nodes]
        self.gridNodes = ids
        for (n1, n2, cd) in ribs:
            O.bodies.append(gridConnection(ids[n1], ids[n2], self.P.rg, material=self.matRib, mask=6, cellDist=Vector3i(*cd)))

    def sphere_tops(self):
        return [O.bodies[i].state.pos[2] + O.bodies[i].shape.radius for i in self.spheres]

    def tick_oedo(self):
        P = self.P
        s = O.forces.f(self.top)[2] / (P.Lx * P.Ly)
        target = self.a.oedo_kpa * 1e3
        if self.oedoDown:
            if s >= target:
                self.oedoDown = False
                self.oedoPeak.append(s)
        elif s <= 0:
            self.oedoDone += 1
            if self.oedoDone == self.a.oedo_cycles:
                O.bodies[self.top].state.vel = Vector3(0, 0, 0)
                self.phase = 'idle'
                stop_after_this_step()
                return
            self.oedoDown = True
        if self.oedoDown:
            v = -0.5 if s < 0.02 * target else -0.1
        else:
            v = 0.1
        O.bodies[self.top].state.vel = Vector3(0, 0, v)

    def generate(self):
        a, P = self.a, self.P
        self.setup_scene()
        self.add_materials()
        self.timed('clouds', self.make_clouds)
        # deposition under gravity
        tDep = math.sqrt(2 * P.H0 / 9.81) + 0.05
        self.timed('deposition', lambda: O.run(int(math.ceil(tDep / P.dt)), True))
        # oedometric load/unload cycles with a huge top plate driven by velocity
        zTop = max(self.sphere_tops()) + 0.2 * P.d
        self.top = O.bodies.append(utils.box((P.cx, P.cy, zTop + 0.01), (50, 50, 0.01), fixed=True, material=self.matGrain, mask=1))
        self.oedoDown, self.oedoDone, self.oedoPeak = True, 0, []
        self.phase = 'oedo'
        cap = int(60.0 / P.dt)
        self.timed('oedometric', lambda: run_until_stopped(cap))
        if self.oedoDone < a.oedo_cycles:
            raise RuntimeError('oedometric cycles not finished within %d steps' % cap)
        # lift the plate 0.1 m at 1 m/s and park it (never erase or teleport it: pitfall 2)
        O.bodies[self.top].state.vel = Vector3(0, 0, 1.0)
        self.timed('lift', lambda: O.run(int(round(0.1 / P.dt)), True))
        O.bodies[self.top].state.vel = Vector3(0, 0, 0)

        def settle():
            O.run(int(round(0.05 / P.dt)), True)
            for _ in range(10):
                if utils.unbalancedForce() < a.settle_tol:
                    break
                O.run(int(round(0.01 / P.dt)), True)
        self.timed('settle', settle)
        self.info['unbalancedForce'] = utils.unbalancedForce()
        self.info['oedoPeak_kPa'] = [s / 1e3 for s in self.oedoPeak]
        self.measure_layer()
        if a.case == 'F':
            zMid = P.Z0 + 0.5 * self.info['layerHeight']
            n = 0
            for i in self.spheres:
                b = O.bodies[i]
                if abs(b.state.pos[2] - zMid) <= P.r:
                    b.state.blockedDOFs = 'xy'
                    v = b.state.vel
                    b.state.vel = Vector3(0, 0, v[2])
                    n += 1
            self.info['F_blocked'] = n
            self.info['F_zMid'] = zMid

    def measure_layer(self):
        P = self.P
        tops = sorted(self.sphere_tops(), reverse=True)
        k = max(1, int(round(0.1 * len(tops))))
        H = sum(tops[:k]) / k - P.Z0
        sph = [(O.bodies[i].state.pos, O.bodies[i].shape.radius) for i in self.spheres]
        vs = sum(4.0 / 3.0 * math.pi * r**3 for _, r in sph)
        self.info['nSpheres'] = len(self.spheres)
        self.info['layerHeight'] = H
        self.info['layerPorosity'] = 1 - vs / (P.Lx * P.Ly * H)
        self.info['layerPorosityClipped'] = box_porosity(sph, (0, 0, P.Z0), (P.Lx, P.Ly, P.Z0 + H), P.Lx, P.Ly)
        self.info['minSphereBottom'] = min(p[2] - r for p, r in sph) - P.Z0
        if self.gridNodes:
            zs = [O.bodies[i].state.pos[2] - P.Z0 for i in self.gridNodes]
            self.info['gridHeight'] = sum(zs) / len(zs)
            self.info['gridHeightMin'] = min(zs)
            self.info['gridHeightMax'] = max(zs)
        print('[study] spheres %d, layer height %.4f m, porosity %.4f (clipped %.4f)%s' % (
            len(self.spheres), H, self.info['layerPorosity'], self.info['layerPorosityClipped'],
            ', grid at %.4f m' % self.info['gridHeight'] if self.gridNodes else ''), flush=True)

    # --- specimen export / import -------------------------------------------------------------
    def specimen(self):
        """Every body and material as plain data (floats written with %.17g by write_json)."""
        mats = []
        for m in O.materials:
            d = {'class': m.__class__.__name__, 'young': m.young, 'poisson': m.poisson, 'frictionAngle': m.frictionAngle,
                 'density': m.density, 'label': m.label}
            if d['class'] == 'CohFrictMat':
                for k in ('isCohesive', 'alphaKr', 'alphaKtw', 'etaRoll', 'etaTwist', 'normalCohesion', 'shearCohesion',
                          'fragile', 'momentRotationLaw'):
                    d[k] = getattr(m, k)
            mats.append(d)
        bodies = []
        for b in O.bodies:
            s = b.state
            q = s.ori
            cls = b.shape.__class__.__name__
            sh = {'class': cls}
            if cls == 'Box':
                sh['extents'] = list(b.shape.extents)
            elif cls in ('Sphere', 'GridNode'):
                sh['radius'] = b.shape.radius
            elif cls == 'GridConnection':
                sh['radius'] = b.shape.radius
                sh['node1'] = b.shape.node1.id
                sh['node2'] = b.shape.node2.id
                sh['cellDist'] = [int(x) for x in b.shape.cellDist]
            elif cls == 'Clump':  # knob --clump-size
                sh['members'] = sorted(int(i) for i in b.shape.members.keys())
            else:
                raise RuntimeError('specimen export: unexpected shape %s' % cls)
            bd = {'id': b.id, 'shape': sh, 'material': -1 if cls == 'Clump' else b.material.id, 'mask': b.mask, 'bounded': b.bounded,
                  'pos': list(s.pos), 'ori': [q[3], q[0], q[1], q[2]], 'vel': list(s.vel), 'angVel': list(s.angVel),
                  'mass': s.mass, 'inertia': list(s.inertia), 'blockedDOFs': s.blockedDOFs}
            if cls == 'Clump':
                bd['angMom'] = list(s.angMom)  # the aspherical integrator's state
            bodies.append(bd)
        P = self.P
        return {'format': 'ryade-study-specimen-1', 'source': 'yade_ref/study/study.py',
                'params': params_dict(self.a, RUN_OPTIONS),
                'Z0': P.Z0, 'cell': list(O.cell.size), 'iter': O.iter, 'time': O.time, 'dt': O.dt,
                'roles': {'spheres': self.spheres, 'top': self.top, 'gridNodes': self.gridNodes},
                'info': self.info, 'materials': mats, 'bodies': bodies}

    def rebuild(self, spec):
        """O.reset() and rebuild the specimen exactly (same ids, same doubles)."""
        P, a = self.P, self.a
        O.reset()
        self.setup_scene(loading=True)
        O.cell.setBox(*spec['cell'])
        O.dt = spec['dt']
        mat = {'FrictMat': FrictMat, 'CohFrictMat': CohFrictMat}
        for m in spec['materials']:
            kw = dict(m)
            if a.load_friction is not None and kw['label'] in ('grain', 'rib'):  # knob --load-friction
                kw['frictionAngle'] = math.radians(a.load_friction)
            if a.eta_roll > 0 and a.roll_plates and kw['label'] == 'grain':  # plates and piston roll-resist too
                kw.update(self.roll_material_kw())
            O.materials.append(mat[kw.pop('class')](**kw))
        sphereMat = None
        if a.eta_roll > 0 and not a.roll_plates:  # knob --eta-roll: the spheres get their own CohFrictMat
            g = [m for m in spec['materials'] if m['label'] == 'grain'][0]
            kw = {k: g[k] for k in ('young', 'poisson', 'frictionAngle', 'density')}
            if a.load_friction is not None:
                kw['frictionAngle'] = math.radians(a.load_friction)
            kw.update(self.roll_material_kw())
            kw.pop('class')
            sphereMat = O.materials.append(CohFrictMat(label='grainRoll', **kw))
        for bd in spec['bodies']:
            sh = bd['shape']
            if sh['class'] == 'Box':
                b = utils.box(bd['pos'], sh['extents'], fixed=True, material=bd['material'], mask=bd['mask'])
            elif sh['class'] == 'Sphere':
                b = utils.sphere(bd['pos'], sh['radius'], material=bd['material'] if sphereMat is None else sphereMat, mask=bd['mask'])
            elif sh['class'] == 'GridNode':
                from yade.gridpfacet import gridNode
                b = gridNode(bd['pos'], sh['radius'], fixed=False, material=bd['material'])
            elif sh['class'] == 'GridConnection':
                from yade.gridpfacet import gridConnection
                from yade.minieigenHP import Vector3i
                b = gridConnection(sh['node1'], sh['node2'], sh['radius'], material=bd['material'], mask=bd['mask'],
                                   cellDist=Vector3i(*sh['cellDist']))
            elif sh['class'] == 'Clump':  # knob --clump-size: the members exist already, at their positions
                i = O.bodies.clump(sh['members'])
                if i != bd['id']:
                    raise RuntimeError('specimen import: clump %d came out as #%d' % (bd['id'], i))
                continue
            i = O.bodies.append(b)
            if i != bd['id']:
                raise RuntimeError('specimen import: body %d came out as #%d' % (bd['id'], i))
        for bd in spec['bodies']:  # states last (gridConnection adds node masses)
            s = O.bodies[bd['id']].state
            if bd['shape']['class'] == 'Clump':
                # keep the frame O.bodies.clump computed (the members' poses in it come with it); the
                # motion is the velocity and the angular momentum
                s.vel = Vector3(*bd['vel'])
                s.angMom = Vector3(*bd['angMom'])
                continue
            s.pos = Vector3(*bd['pos'])
            w, x, y, z = bd['ori']
            s.ori = Quaternion(w, x, y, z)
            s.vel = Vector3(*bd['vel'])
            s.angVel = Vector3(*bd['angVel'])
            s.mass = bd['mass']
            s.inertia = Vector3(*bd['inertia'])
            s.blockedDOFs = bd['blockedDOFs']
        roles = spec['roles']
        self.spheres, self.top, self.gridNodes = roles['spheres'], roles['top'], roles['gridNodes']
        if a.block_rotations:  # knob: spheres that cannot rotate (F's 'xy' stays)
            for i in self.spheres:
                st = O.bodies[i].state
                st.blockedDOFs = st.blockedDOFs + 'XYZ'
                st.angVel = Vector3(0, 0, 0)
        if a.grid_block:  # diagnostic knob: grid nodes held along the given DOFs (their velocity there zeroed)
            if not self.gridNodes:
                raise RuntimeError('--grid-block: the specimen has no grid nodes (case %s)' % a.case)
            for i in self.gridNodes:
                st = O.bodies[i].state
                st.blockedDOFs = a.grid_block
                v, w = st.vel, st.angVel
                st.vel = Vector3(*[0.0 if c in a.grid_block else v[k] for k, c in enumerate('xyz')])
                st.angVel = Vector3(*[0.0 if c in a.grid_block else w[k] for k, c in enumerate('XYZ')])
        if a.grid_kn_scale != 1 or a.grid_kr_scale != 1:  # knob: geogrid bond stiffness (as calibration connect())
            n = 0
            for bd in spec['bodies']:
                if bd['shape']['class'] == 'GridConnection':
                    ph = O.interactions[bd['shape']['node1'], bd['shape']['node2']].phys
                    ph.kn *= a.grid_kn_scale
                    ph.ks *= a.grid_kn_scale
                    ph.kr *= a.grid_kr_scale
                    ph.ktw *= a.grid_kr_scale
                    n += 1
            if n == 0:
                raise RuntimeError('--grid-kn-scale/--grid-kr-scale: the specimen has no grid bonds (case %s)' % a.case)

    def roll_material_kw(self):
        """CohFrictMat fields of a non-cohesive rolling-resistant material (knob --eta-roll): moments on,
        plastic rolling limit etaRoll*R*|Fn|, no twisting moment (alphaKtw = 0), no cohesion."""
        a = self.a
        return {'class': 'CohFrictMat', 'isCohesive': False, 'normalCohesion': 0.0, 'shearCohesion': 0.0, 'momentRotationLaw': True,
                'alphaKr': a.alpha_kr, 'etaRoll': a.eta_roll, 'alphaKtw': 0.0, 'etaTwist': -1.0}

    # --- loading ------------------------------------------------------------------------------
    def pressure(self):
        f = O.forces.f
        return sum(f(i)[2] for i in self.piston) / self.P.A

    def p_target(self, t):
        a = self.a
        lo, hi = a.seat_kpa * 1e3, a.peak_kpa * 1e3
        if t < 0:
            return lo
        ph = (t * a.freq) % 1.0
        if a.wave == 'haversine':
            return lo + (hi - lo) * math.sin(math.pi * ph)**2
        return lo + (hi - lo) * (1 - abs(2 * ph - 1))

    def set_piston_vel(self, v):
        vv = Vector3(0, 0, v)
        for b in self.pistonBodies:
            b.state.vel = vv

    def piston_bottom(self):
        return O.bodies[self.piston[0]].state.pos[2] + self.pistonOff

    def tick(self):
        if self.sub is not None:
            self.tick_subgrade()
        if self.phase == 'idle':
            return
        if self.phase == 'oedo':
            return self.tick_oedo()
        P, a = self.P, self.a
        vNow = O.bodies[self.piston[0]].state.vel[2]  # the piston velocity of this step
        p = self.pressure()
        self.pf += P.alpha * (p - self.pf)
        m = O.iter - self.iterSeatEnd  # steps since the end of seating (negative before)
        t = m * P.dt
        phase = self.phase
        if self.phase == 'approach':
            target = a.seat_kpa * 1e3
            if p >= target:
                self.phase = 'idle'
                stop_after_this_step()
            self.set_piston_vel(-0.1)
        else:
            target = a.seat_kpa * 1e3 if self.phase == 'seat' else self.p_target(t)
            e = target - self.pf
            self.I += e * P.dt
            v = -(P.Kp * e + P.Ki * self.I)
            v = max(-a.vmax, min(a.vmax, v))
            if a.controller != 'servopid':  # pi, or native run by this PyRunner (native_piston())
                self.set_piston_vel(v)
            else:
                servo.target = target * P.A
            if self.phase == 'cycle':
                c = self.cyc
                c['n'] += 1
                c['peak'] = max(c['peak'], self.pf)
                c['peakRaw'] = max(c['peakRaw'], p)
                c['se'] += (self.pf - target)**2
                c['seRaw'] += (p - target)**2
                zb = self.piston_bottom()
                c['maxRut'] = max(c['maxRut'], self.zRef - zb)
                if self.zRef - zb > a.stop_rut:
                    self.stopped = True
                    self.phase = 'idle'
                    stop_after_this_step()
        if O.iter % a.steps_every == 0:
            self.steps.append([O.iter, phase, p / 1e3, self.pf / 1e3, target / 1e3, self.piston_bottom() - P.Z0, vNow])

    def start_subgrade(self):
        """Knob --subgrade-k: the bottom plate stays a kinematic (blocked) body, as the piston is, but
        its velocity is integrated here every step from its own equation of motion
            m_p dv/dt = F_c + P0 - K A u - c v,   u = z - z0 (z0: its position at the start of loading),
        F_c the contact force on it (O.forces.f after NewtonIntegrator, this step's forces), K A u a
        Winkler spring bed (A = Lx Ly), P0 = the weight of the layer (spheres and grid) so that u = 0 is
        the equilibrium under self weight, c = 2 zeta sqrt(K A m_p) a dashpot. The velocity set here
        is used by the next step's NewtonIntegrator (one-step lag, explicit). The same arithmetic runs in
        both engines (here, or in ryade's RyadePistonController with --controller native, in this
        order), so nothing depends on how an engine applies forces to a blocked body."""
        a, P = self.a, self.P
        plate = [b.id for b in O.bodies if b.shape.__class__.__name__ == 'Box' and b.id != self.top]
        if len(plate) != 1:
            raise RuntimeError('--subgrade-k: expected one bottom plate, found %r' % plate)
        mLayer = sum(O.bodies[i].state.mass for i in self.spheres + self.gridNodes)
        m = a.subgrade_mass if a.subgrade_mass is not None else 0.1 * mLayer
        KA = a.subgrade_k * P.Lx * P.Ly
        w = math.sqrt(KA / m)
        if w * P.dt > 0.05:  # the plate's own spring-mass oscillation must be far below the step limit
            raise RuntimeError('--subgrade-k: omega dt = %.3g > 0.05; raise --subgrade-mass' % (w * P.dt))
        self.sub = {'id': plate[0], 'm': m, 'KA': KA, 'c': 2 * a.subgrade_zeta * math.sqrt(KA * m), 'P0': 9.81 * mLayer,
                    'u': 0.0, 'v': 0.0}
        self.info['subgrade'] = {'plate': plate[0], 'mass': m, 'KA': KA, 'c': self.sub['c'], 'P0': self.sub['P0'],
                                 'omega_dt': w * P.dt, 'layerMass': mLayer}

    def tick_subgrade(self):
        s, dt = self.sub, self.P.dt
        f = O.forces.f(s['id'])[2] + s['P0'] - s['KA'] * s['u'] - s['c'] * s['v']
        s['u'] += dt * s['v']  # what NewtonIntegrator did to the plate this step
        s['v'] += dt * f / s['m']
        O.bodies[s['id']].state.vel = Vector3(0, 0, s['v'])

    def native_piston(self):
        """--controller native: the PyRunner of the loading is replaced by ryade's RyadePistonController
        engine at its place in O.engines, which does what tick() does in the phases approach, seat and
        cycle (src/piston.rs), and tick_subgrade() with --subgrade-k, without a Python call per step. None
        where the PyRunner law runs instead: under YADE (no such class)."""
        a, P = self.a, self.P
        if a.controller != 'native':
            return None
        import yade
        Native = getattr(yade, 'RyadePistonController', None)  # a ryade extension: only ryade's yade has it
        if Native is None:
            print('[study] --controller native: YADE has no RyadePistonController (a ryade extension); the PyRunner runs the law, as --controller pi', flush=True)
            return None
        # it runs when the PyRunner would have (PeriodicEngine's rule: a fresh one skips its first step)
        pc = Native(iterPeriod=ctl.iterPeriod, nDone=ctl.nDone, iterLast=ctl.iterLast, ids=self.piston, area=P.A, alpha=P.alpha, Kp=P.Kp, Ki=P.Ki, vmax=a.vmax, dt=P.dt, pSeat=a.seat_kpa * 1e3,
                    pPeak=a.peak_kpa * 1e3, freq=a.freq, wave=a.wave, vApproach=-0.1, stopRut=a.stop_rut, pistonOff=self.pistonOff,
                    Z0=P.Z0, stepsEvery=a.steps_every, label='piston')
        if self.sub is not None:  # the spring bed's state so far (tick_subgrade's, none yet at load())
            s = self.sub
            pc.subId, pc.subM, pc.subKA, pc.subC, pc.subP0, pc.subU, pc.subV = s['id'], s['m'], s['KA'], s['c'], s['P0'], s['u'], s['v']
        O.engines = [pc if e is ctl else e for e in O.engines]
        print('[study] --controller native: RyadePistonController (ryade engine) runs the law in place of the PyRunner', flush=True)
        return pc

    def native_collect(self, pc):
        """--controller native, after a run: the steps.csv samples, the phase, the stop and the cycle's
        statistics (self.cyc) as tick() leaves them."""
        self.steps += pc.takeSteps()
        self.phase, self.stopped, self.pf, self.I = pc.phase, pc.stopped, pc.pf, pc.I
        if self.sub is not None:
            self.sub['u'], self.sub['v'] = pc.subU, pc.subV
        return {'n': pc.n, 'peak': pc.peak, 'peakRaw': pc.peakRaw, 'se': pc.se, 'seRaw': pc.seRaw, 'maxRut': pc.maxRut}

    def load(self):
        a, P = self.a, self.P
        if a.subgrade_k > 0:
            self.start_subgrade()
        tops = self.sphere_tops()
        zb = max(tops) + 0.05 * P.d
        self.piston = O.bodies.append(geom.facetCylinder((P.cx, P.cy, zb + 0.025), radius=P.D / 2, height=0.05, segmentsNumber=24,
                                                         wallMask=2 | 4, material=self.matGrainId, mask=1))
        self.pistonBodies = [O.bodies[i] for i in self.piston]
        self.pistonOff = zb - O.bodies[self.piston[0]].state.pos[2]
        if a.controller == 'servopid':
            servo.ids = self.piston
        pc = self.native_piston()
        self.pc = pc  # also measures the porosity (boxPorosity, the same bits as box_porosity below)
        self.pf, self.I = 0.0, 0.0
        self.iterSeatEnd = 10**12
        self.steps = []
        self.stopped = False
        # approach at 0.1 m/s until the raw pressure reaches the seating pressure
        self.phase = 'approach'
        if pc:
            pc.phase = 'approach'
        cap = int(math.ceil((zb - P.Z0) / 0.1 / P.dt))
        self.timed('approach', lambda: run_until_stopped(cap))
        if pc:
            self.native_collect(pc)
        if self.phase != 'idle':
            raise RuntimeError('piston approach: no contact within %d steps' % cap)
        # seating: PI on the seating pressure for one period
        self.iterSeatEnd = O.iter + P.stepsPerCycle
        self.phase = 'seat'
        if pc:
            pc.iterSeatEnd, pc.phase = self.iterSeatEnd, 'seat'
        if a.controller == 'servopid':
            self.set_piston_vel(0.0)
            servo.target = a.seat_kpa * 1e3 * P.A
            servo.dead = False
        self.timed('seating', lambda: O.run(P.stepsPerCycle, True))
        if pc:
            self.native_collect(pc)
        self.zRef = self.piston_bottom()
        if pc:
            pc.zRef = self.zRef
        ref = {i: O.bodies[i].state.pos for i in self.spheres}
        self.profileAt = None
        P.Kp0, P.Ki0, self.gainScale, self.gainChanges = P.Kp, P.Ki, 1.0, []  # --adapt-gains scales from these
        self.rows = [self.history_row(0, {'n': 0})]
        t0, c0 = time.time(), time.process_time()
        it0 = O.iter
        for k in range(1, a.cycles + 1):
            self.cyc = {'n': 0, 'peak': -1e300, 'peakRaw': -1e300, 'se': 0.0, 'seRaw': 0.0, 'maxRut': -1e300}
            self.phase = 'cycle'
            if pc:
                pc.resetCycle()
                pc.phase = 'cycle'
            run_until_stopped(P.stepsPerCycle)
            if pc:
                self.cyc = self.native_collect(pc)
            self.rows.append(self.history_row(k, self.cyc))
            r = self.rows[-1]
            print('[study] cycle %3d rut %7.2f mm peak %6.1f kPa rms %6.1f kPa porosity %.4f' % (
                k, r['rut_mm'], r['peak_kPa'], r['tracking_rms_kPa'], r['porosity_box']), flush=True)
            if a.adapt_gains > 0:
                self.adapt_gains(k, r, pc)
            if k == a.profile_cycle:  # the paper's Fig 7 is the field at cycle 100
                self.profileAt = self.displacement_profile(ref)
            if self.stopped:
                print('[study] rut above %.3f m: stopped in cycle %d' % (a.stop_rut, k), flush=True)
                break
        self.phase = 'idle'
        if pc:
            pc.phase = 'idle'
        self.timings.append(('cycles', O.iter - it0, time.time() - t0, time.process_time() - c0))
        print('[study] %-12s %7d steps %8.2f s wall %8.2f s cpu' % ('cycles', O.iter - it0, time.time() - t0, time.process_time() - c0), flush=True)
        self.profile = self.displacement_profile(ref)

    def adapt_gains(self, k, row, pc):
        """Knob --adapt-gains X: after a cycle whose filtered peak missed the target peak by more than the
        fraction X, scale both PI gains by 1.1 (peak short) or 1/1.1 (peak over), within [0.5, 4] times the
        initial gains; the next cycle runs with them. A cycle inside the band changes nothing, so a run that
        never leaves it is the same, bit for bit, as one without the knob."""
        a, P = self.a, self.P
        ratio = row['peak_kPa'] / a.peak_kpa
        if not (ratio < 1 - a.adapt_gains or ratio > 1 + a.adapt_gains):
            return
        scale = min(4.0, max(0.5, self.gainScale * (1.1 if ratio < 1 else 1 / 1.1)))
        if scale == self.gainScale:
            return
        self.gainScale = scale
        P.Kp, P.Ki = P.Kp0 * scale, P.Ki0 * scale
        if pc:
            pc.Kp, pc.Ki = P.Kp, P.Ki
        self.gainChanges.append([k, scale])
        print('[study] cycle %3d peak %.1f kPa (%.0f %% of the target): PI gains x %.3f of the initial' % (
            k, row['peak_kPa'], 100 * ratio, scale), flush=True)

    def history_row(self, k, c):
        P = self.P
        zb = self.piston_bottom()
        zBot = P.Z0 + (self.sub['u'] if self.sub else 0.0)  # the plate top
        lo = (P.cx - P.D / 2, P.cy - P.D / 2, zBot)
        hi = (P.cx + P.D / 2, P.cy + P.D / 2, zb)
        if self.pc is not None:  # --controller native under ryade: the same formula in the Rust core
            porosity = self.pc.boxPorosity(self.spheres, lo, hi, P.Lx, P.Ly, GL_X, GL_W)
        else:
            sph = [(O.bodies[i].state.pos, O.bodies[i].shape.radius) for i in self.spheres]
            porosity = box_porosity(sph, lo, hi, P.Lx, P.Ly)
        n = c['n']
        row = {'cycle': k, 'complete': 0 if self.stopped else 1, 'steps': n, 'time_s': (O.iter - self.iterSeatEnd) * P.dt,
               'rut_mm': (self.zRef - zb) * 1e3,
               'rut_max_mm': c['maxRut'] * 1e3 if n else float('nan'),
               'peak_kPa': c['peak'] / 1e3 if n else float('nan'),
               'peak_raw_kPa': c['peakRaw'] / 1e3 if n else float('nan'),
               'tracking_rms_kPa': math.sqrt(c['se'] / n) / 1e3 if n else float('nan'),
               'tracking_rms_raw_kPa': math.sqrt(c['seRaw'] / n) / 1e3 if n else float('nan'),
               'porosity_box': porosity,
               'piston_z_m': zb - P.Z0}
        if self.gridNodes:
            zs = [O.bodies[i].state.pos[2] - P.Z0 for i in self.gridNodes]
            row['grid_z_m'] = sum(zs) / len(zs)
        if self.sub:
            row['subgrade_mm'] = self.sub['u'] * 1e3
        return row

    def displacement_profile(self, ref):
        """Final displacement since the end of seating by depth below the piston at that time:
        spheres under the piston footprint (horizontal distance to the axis < D/2) and outside it."""
        P = self.P
        nb = int(math.ceil((self.zRef - P.Z0) / P.d))
        acc = [[0, 0.0, 0.0, 0, 0.0, 0.0] for _ in range(nb)]
        for i in self.spheres:
            p0, p1 = ref[i], O.bodies[i].state.pos
            dx = p0[0] - P.cx
            dy = p0[1] - P.cy
            dx -= P.Lx * round(dx / P.Lx)
            dy -= P.Ly * round(dy / P.Ly)
            rad = math.hypot(dx, dy)
            depth = self.zRef - p0[2]
            k = min(nb - 1, max(0, int(depth / P.d)))
            uz = p1[2] - p0[2]
            ur = ((p1[0] - p0[0]) * dx + (p1[1] - p0[1]) * dy) / rad if rad > 0 else 0.0
            o = 0 if rad < P.D / 2 else 3
            acc[k][o] += 1
            acc[k][o + 1] += uz
            acc[k][o + 2] += ur
        rows = []
        for k, (n1, uz1, ur1, n2, uz2, ur2) in enumerate(acc):
            rows.append({'depth_top_m': k * P.d, 'depth_bot_m': (k + 1) * P.d,
                         'n_under': n1, 'uz_under_mm': uz1 / n1 * 1e3 if n1 else float('nan'),
                         'ur_under_mm': ur1 / n1 * 1e3 if n1 else float('nan'),
                         'n_outside': n2, 'uz_outside_mm': uz2 / n2 * 1e3 if n2 else float('nan'),
                         'ur_outside_mm': ur2 / n2 * 1e3 if n2 else float('nan')})
        return rows


# ----------------------------------------------------------------------------------------------
# output


def fmt(x):
    if isinstance(x, bool):
        return 'true' if x else 'false'
    if isinstance(x, int):
        return str(x)
    if isinstance(x, float):
        if x != x or x in (float('inf'), float('-inf')):
            return 'null'
        return '%.17g' % x
    if isinstance(x, str):
        return json.dumps(x)
    if x is None:
        return 'null'
    if isinstance(x, dict):
        return '{' + ', '.join('%s: %s' % (json.dumps(str(k)), fmt(v)) for k, v in x.items()) + '}'
    if isinstance(x, (list, tuple)):
        return '[' + ', '.join(fmt(v) for v in x) + ']'
    raise TypeError('cannot write %r' % (x,))


def write_json(path, obj):
    with open(path + '.tmp', 'w') as f:
        if isinstance(obj, dict) and 'bodies' in obj:  # one body per line
            items = ['  %s: %s' % (json.dumps(k), fmt(v)) for k, v in obj.items() if k != 'bodies']
            items.append('  "bodies": [\n' + ',\n'.join('    ' + fmt(b) for b in obj['bodies']) + '\n  ]')
            f.write('{\n' + ',\n'.join(items) + '\n}\n')
        else:
            f.write(fmt(obj) + '\n')
    os.replace(path + '.tmp', path)


def write_csv(path, rows, cols=None, ffmt='%.17g'):
    cols = cols or list(rows[0].keys())
    with open(path + '.tmp', 'w') as f:
        f.write(','.join(cols) + '\n')
        for r in rows:
            vals = r if isinstance(r, (list, tuple)) else [r.get(c, '') for c in cols]
            f.write(','.join((ffmt % v if v == v else 'nan') if isinstance(v, float) else str(v) for v in vals) + '\n')
    os.replace(path + '.tmp', path)


# ----------------------------------------------------------------------------------------------
# main

args = parse_args(sys.argv[1:])
spec = getattr(args, 'specimen', None)
if spec is not None:
    del args.specimen
os.makedirs(args.out, exist_ok=True)
P = Params(args)
study = Study(args, P)
T0, C0 = time.time(), time.process_time()
print('[study] ratio %.2f case %s size %s seed %d: d %.4f m, cell %.4f x %.4f x %.4f m, %d spheres, dt %.6g s (%d steps per cycle), Kp %.4g'
      % (args.ratio, args.case, args.size, args.seed, P.d, P.Lx, P.Ly, P.Lz, P.nSpheres, P.dt, P.stepsPerCycle, P.Kp), flush=True)
if spec is None:
    study.generate()
    spec = study.specimen()
    if args.export_specimen:
        write_json(args.export_specimen, spec)
else:
    study.info = dict(spec['info'])
if not args.generate_only:
    if args.import_specimen or not args.no_rebuild:
        study.timed('rebuild', lambda: study.rebuild(spec))
    study.matGrainId = [m['label'] for m in spec['materials']].index('grain')  # 0
    study.load()
    write_csv(os.path.join(args.out, 'history.csv'), study.rows,
              ['cycle', 'complete', 'steps', 'time_s', 'rut_mm', 'rut_max_mm', 'peak_kPa', 'peak_raw_kPa', 'tracking_rms_kPa',
               'tracking_rms_raw_kPa', 'porosity_box', 'piston_z_m'] + (['grid_z_m'] if study.gridNodes else [])
              + (['subgrade_mm'] if study.sub else []))
    steps = [[r[0], r[1], (r[0] - study.iterSeatEnd) * P.dt] + r[2:] for r in study.steps]
    write_csv(os.path.join(args.out, 'steps.csv'), steps,
              ['iter', 'phase', 't_s', 'p_raw_kPa', 'p_filtered_kPa', 'p_target_kPa', 'piston_z_m', 'v_mps'], '%.10g')
    write_csv(os.path.join(args.out, 'profile.csv'), study.profile)
    if study.profileAt is not None:
        write_csv(os.path.join(args.out, 'profile_c%d.csv' % args.profile_cycle), study.profileAt)
summary = {'params': params_dict(args),
           'derived': {'d': P.d, 'Lx': P.Lx, 'Ly': P.Ly, 'Lz': P.Lz, 'Z0': P.Z0, 'D': P.D, 'nSpheres': P.nSpheres, 'H0': P.H0,
                       'zGrid0': P.zGrid, 'dt': P.dt, 'stepsPerCycle': P.stepsPerCycle, 'mNode': P.mNode, 'Kp': P.Kp, 'Ki': P.Ki,
                       'alpha': P.alpha},
           'generation': study.info,
           'timings': [{'phase': n, 'steps': s, 'wall_s': w, 'cpu_s': c} for n, s, w, c in study.timings],
           'wall_s': time.time() - T0, 'cpu_s': time.process_time() - C0}
if not args.generate_only:
    summary['loading'] = {'stopped': study.stopped, 'cycles_run': study.rows[-1]['cycle'], 'final_rut_mm': study.rows[-1]['rut_mm']}
    if args.adapt_gains:
        summary['loading']['gain_changes'] = study.gainChanges  # [cycle after which, gain scale]
write_json(os.path.join(args.out, 'summary.json'), summary)
print('[study] done in %.1f s, outputs in %s' % (time.time() - T0, args.out), flush=True)
