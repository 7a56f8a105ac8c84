# Drained triaxial compression of the study's aggregate in a periodic cell (YADE's PeriTriaxController),
# an element test that gives the granular model's peak and critical-state friction angles and its
# dilatancy. One plain YADE 2023.02a script, unchanged in YADE and ryade:
#
#   yade -n -x yade_ref/calibration/triaxial.py -- [--variant plain,roll0.5 ...] [--quick] [--out DIR]
#   compat run yade_ref/calibration/triaxial.py -- <same arguments>
#   compat calibrate --triaxial        (runs the variants, writes the table, the CSV and the plot)
#
# Material (the study's aggregate, /work/shared/study.md): mono-sized spheres d = 0.03 m (ratio 0.5),
# FrictMat(young=1e8, poisson=0.25, frictionAngle=30 deg, density=2650), local damping 0.2.
# Variants (--variant, comma-separated):
#   plain        spheres, Cundall-Strack;
#   rollX        spheres with rolling resistance as the study's --eta-roll X knob (yade_ref/study/README.md):
#                CohFrictMat(momentRotationLaw=True, etaRoll=X, alphaKr=2, alphaKtw=0, isCohesive=False,
#                normalCohesion=shearCohesion=0), Ig2_Sphere_Sphere_ScGeom6D,
#                Ip2_CohFrictMat_CohFrictMat_CohFrictPhys, Law2_ScGeom6D_CohFrictPhys_CohesionMoment(
#                always_use_moment_law=True, useIncrementalForm=True); X = 0.25, 0.5, 1;
#   clumpK       clumps of K = 2, 3, 4 equal spheres built as the study's --clump-size K (each makeCloud sphere of
#                radius R becomes K spheres of radius R/K^(1/3) at distance R - R/K^(1/3) from its centre along K
#                regular directions turned by a random rotation from Python's Mersenne Twister).
#
# Procedure (one variant):
#  1. Packing: makeCloud (mono-sized, periodic, seed --seed) at solid fraction --cloud-fraction, compacted by a
#     PeriTriaxController to an isotropic --p0 (default 100 kPa) with the test's friction (spheres: plain
#     Cundall-Strack; clumps: the clumps themselves) until the stress is within 1 % and the unbalanced force below
#     --unbalanced. The sphere variants share this packing: --cache DIR keeps it (JSON, exact doubles).
#  2. Rebuild: a fresh scene with the variant's material and functors at the packed positions, at rest (contacts
#     re-detected, as the study's specimen rebuild does), re-consolidated at p0 to the same criteria.
#  3. Shear: lateral stresses held at p0 (stressMask 3, stiffness servo), axial logarithmic strain imposed at
#     --rate up to --eps-max. --rate default: inertial number I = rate d / sqrt(p0/rho) = --inertial (1e-3,
#     quasi-static). Every 0.1 % of axial strain a row: strains from Cell.trsf (logarithmic, compression
#     positive, relative to the start of shear), stresses from utils.getStress() (compression positive).
#
# Results per variant (the definitions live here, in one place):
#   sin(phi_mob) = (s1 - s3)/(s1 + s3), s1 axial, s3 the mean lateral stress; q = s1 - s3, p = (s1 + 2 s3)/3;
#   phi_peak  = asin(max of sin(phi_mob) smoothed over 5 rows = 0.5 % strain);
#   phi_cv    = asin(mean of sin(phi_mob) over the last 0.05 of axial strain);
#   psi_max   = max over windows of 0.02 axial strain of asin(-s/(2 - s)), s = d(eps_v)/d(eps_a) by least
#               squares (triaxial dilatancy angle; eps_v = -ln(V/V0) compression positive, so dilation is s < 0);
#   n0        = porosity at the start of shear (clumps: the union volume of each clump's spheres, estimated once on a
#               grid; YADE's clump mass counts the overlaps twice).
# Outputs in --out: <variant>.curve.csv (one row per 0.1 % axial strain) and <variant>.summary.json (doubles as
# %.17g through json; no wall times, so both engines write the same bytes).
import argparse, json, math, os, random, sys

from yade import pack, utils

VARIANTS = ('plain', 'roll0.25', 'roll0.5', 'roll1', 'clump2', 'clump3', 'clump4')
DEFAULT_VARIANTS = 'plain,roll0.25,roll0.5,roll1,clump3'
CURVE_COLS = ('step', 'eps_a', 'eps_v', 'eps_x', 'eps_y', 'sig1_kPa', 'sig3_kPa', 'p_kPa', 'q_kPa', 'q_over_p',
              'sin_phi', 'porosity', 'unbalanced', 'contacts')


def parse_args(argv):
    ap = argparse.ArgumentParser(prog='triaxial.py', description='Periodic drained triaxial test of the study aggregate '
                                 '(PeriTriaxController); see the header of this file.')
    ap.add_argument('--variant', default=DEFAULT_VARIANTS,
                    help='comma-separated, from: %s (default %s)' % (', '.join(VARIANTS), DEFAULT_VARIANTS))
    ap.add_argument('--quick', action='store_true', help='small fast version: 150 particles, eps_max 0.15, I = 5e-3')
    ap.add_argument('--n', type=int, default=None, help='particles (default 1000; --quick 150)')
    ap.add_argument('--seed', type=int, default=1, help='makeCloud seed (and the clump rotations)')
    ap.add_argument('--d', type=float, default=0.03, help='sphere diameter [m] (the study, ratio 0.5)')
    ap.add_argument('--young', type=float, default=1e8)
    ap.add_argument('--poisson', type=float, default=0.25, help='ks/kn')
    ap.add_argument('--friction', type=float, default=30.0, help='interparticle friction angle [deg]')
    ap.add_argument('--density', type=float, default=2650.0)
    ap.add_argument('--damping', type=float, default=0.2, help='NewtonIntegrator local damping')
    ap.add_argument('--alpha-kr', type=float, default=2.0, help='CohFrictMat alphaKr of the roll variants')
    ap.add_argument('--p0', type=float, default=100e3, help='confining (isotropic and lateral) stress [Pa]')
    ap.add_argument('--eps-max', type=float, default=None, help='final axial log strain (default 0.3; --quick 0.15)')
    ap.add_argument('--inertial', type=float, default=None, help='target inertial number (default 1e-3; --quick 5e-3)')
    ap.add_argument('--rate', type=float, default=None, help='axial strain rate [1/s] (default: from --inertial)')
    ap.add_argument('--lateral-rate', type=float, default=2.0, help='lateral maxStrainRate as a multiple of --rate')
    ap.add_argument('--cloud-fraction', type=float, default=0.25, help='solid fraction of the makeCloud cloud')
    ap.add_argument('--compact-rate', type=float, default=1.0, help='maxStrainRate of the compaction [1/s]')
    ap.add_argument('--unbalanced', type=float, default=0.02, help='unbalanced force that ends compaction and re-consolidation')
    ap.add_argument('--stress-tol', type=float, default=0.02, help='relative stress tolerance of compaction and re-consolidation')
    ap.add_argument('--dt-factor', type=float, default=0.5, help='dt = dt_factor * PWaveTimeStep()')
    ap.add_argument('--out', default='triaxial_out', help='output folder')
    ap.add_argument('--cache', default=None, help='folder for the compacted packings (reused by later runs)')
    a = ap.parse_args(argv)
    if a.n is None:
        a.n = 150 if a.quick else 1000
    if a.eps_max is None:
        a.eps_max = 0.15 if a.quick else 0.3
    if a.inertial is None:
        a.inertial = 5e-3 if a.quick else 1e-3
    if a.rate is None:
        a.rate = a.inertial * math.sqrt(a.p0 / a.density) / a.d
    a.variants = [v.strip() for v in a.variant.split(',') if v.strip()]
    for v in a.variants:
        if v not in VARIANTS:
            ap.error('unknown variant %r; choose from %s' % (v, ', '.join(VARIANTS)))
    if a.n < 8:
        ap.error('--n must be at least 8')
    if not (0 < a.eps_max < 1):
        ap.error('--eps-max must be in (0, 1)')
    if not (0 < a.cloud_fraction < 0.35):
        ap.error('--cloud-fraction must be in (0, 0.35): makeCloud cannot place mono-sized spheres much denser')
    return a


def say(a, variant, msg):
    print('[triaxial %s] %s' % (variant, msg))
    sys.stdout.flush()


# ------------------------------------------------------------------------------------------------
# particles

CLUMP_DIRS = {2: [(1.0, 0.0, 0.0), (-1.0, 0.0, 0.0)],
              3: [(1.0, 0.0, 0.0), (-0.5, math.sqrt(3) / 2, 0.0), (-0.5, -math.sqrt(3) / 2, 0.0)],
              4: [(s3 * x, s3 * y, s3 * z) for s3 in (1 / math.sqrt(3),)
                  for (x, y, z) in ((1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1))]}


def variant_kind(v):
    """('spheres', eta_roll) or ('clump', K)."""
    if v.startswith('clump'):
        return 'clump', int(v[5:])
    if v.startswith('roll'):
        return 'spheres', float(v[4:])
    return 'spheres', 0.0


def clump_members(c, rad, K, rng):
    """The study's --clump-size K clump of the sphere (c, rad): K member centres and the member radius. The same
    construction and random draws as yade_ref/study/study.py's make_clumps (that script runs when imported, so it
    cannot be shared)."""
    rm = rad / K ** (1.0 / 3.0)
    off = rad - rm
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    qx, qy = math.sqrt(1 - u1) * math.sin(2 * math.pi * u2), math.sqrt(1 - u1) * math.cos(2 * math.pi * u2)
    qz, qw = math.sqrt(u1) * math.sin(2 * math.pi * u3), math.sqrt(u1) * math.cos(2 * math.pi * u3)
    R = ((1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)),
         (2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)),
         (2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)))
    out = []
    for d in CLUMP_DIRS[K]:
        e = [R[i][0] * d[0] + R[i][1] * d[1] + R[i][2] * d[2] for i in range(3)]
        out.append((c[0] + off * e[0], c[1] + off * e[1], c[2] + off * e[2]))
    return out, rm


def clump_volume_fraction(K, m=80):
    """Union volume of a K-clump over the volume of its parent sphere (radius 1), counted on an m^3 grid of
    cell centres over the parent's bounding cube (integer counts: the same in every engine)."""
    rm = 1.0 / K ** (1.0 / 3.0)
    cs = [tuple((1.0 - rm) * x for x in d) for d in CLUMP_DIRS[K]]
    h = 2.0 / m
    rm2 = rm * rm
    inside = 0
    for i in range(m):
        x = -1.0 + (i + 0.5) * h
        for j in range(m):
            y = -1.0 + (j + 0.5) * h
            for k in range(m):
                z = -1.0 + (k + 0.5) * h
                for (cx, cy, cz) in cs:
                    if (x - cx) ** 2 + (y - cy) ** 2 + (z - cz) ** 2 <= rm2:
                        inside += 1
                        break
    return inside * h ** 3 / (4.0 / 3.0 * math.pi)


# ------------------------------------------------------------------------------------------------
# scene

def frict_mat(a):
    return FrictMat(young=a.young, poisson=a.poisson, frictionAngle=math.radians(a.friction), density=a.density)


def roll_mat(a, eta):
    """The study's roll_material_kw (knob --eta-roll) on the aggregate's material."""
    return CohFrictMat(young=a.young, poisson=a.poisson, frictionAngle=math.radians(a.friction), density=a.density,
                       isCohesive=False, normalCohesion=0.0, shearCohesion=0.0, momentRotationLaw=True,
                       alphaKr=a.alpha_kr, etaRoll=eta, alphaKtw=0.0, etaTwist=-1.0)


def engines(a, eta, triax, runners):
    if eta > 0:
        il = InteractionLoop([Ig2_Sphere_Sphere_ScGeom6D()],
                             [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=False, setCohesionOnNewContacts=False)],
                             [Law2_ScGeom6D_CohFrictPhys_CohesionMoment(always_use_moment_law=True, useIncrementalForm=True)])
    else:
        il = InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                             [Law2_ScGeom_FrictPhys_CundallStrack()])
    return [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]), il, triax] + runners + \
        [NewtonIntegrator(damping=a.damping)]


def iso_controller(a, rate, hook):
    p0 = a.p0
    return PeriTriaxController(label='triax', goal=(-p0, -p0, -p0), stressMask=7, maxStrainRate=(rate, rate, rate),
                               maxUnbalanced=a.unbalanced, relStressTol=a.stress_tol, absStressTol=a.stress_tol * p0,
                               globUpdate=1, doneHook=hook)


STATE = {}


def phase_done():
    """doneHook of the compaction and re-consolidation: stop the run (O.pause) and stop firing."""
    STATE['done'] = True
    triax.doneHook = ''
    O.pause()


def progress(variant, phase):
    s = utils.getStress()
    p = -(s[0, 0] + s[1, 1] + s[2, 2]) / 3.0
    print('[triaxial %s] %s: step %d, p %.4g kPa, porosity %.4f, unbalanced %.3g, contacts %d'
          % (variant, phase, O.iter, p / 1e3, porosity(), utils.unbalancedForce(), O.interactions.countReal()))
    sys.stdout.flush()


def run_phase(a, variant, phase, max_steps):
    STATE['done'] = False
    start = O.iter
    while not STATE['done']:
        if O.iter - start >= max_steps:
            s = utils.getStress()
            raise SystemExit('triaxial.py: %s of %s did not converge in %d steps (stress %s kPa, goal %.4g kPa, unbalanced %.3g '
                             '> %.3g?); raise --unbalanced or lower --compact-rate'
                             % (phase, variant, max_steps, ' '.join('%.4g' % (-s[i, i] / 1e3) for i in range(3)), a.p0 / 1e3,
                                utils.unbalancedForce(), a.unbalanced))
        O.run(1000, True)
    return O.iter - start


FRACTIONS = {}


def set_solid_volume(a, kind, K):
    """Solid volume of the --n particles (clumps: union of the members, clump_volume_fraction)."""
    f = 1.0
    if kind == 'clump':
        if K not in FRACTIONS:
            FRACTIONS[K] = clump_volume_fraction(K)
        f = FRACTIONS[K]
    STATE['solid'] = a.n * (math.pi * a.d ** 3 / 6) * f


def solid_volume():
    return STATE['solid']


def porosity():
    v = O.cell.volume
    return (v - solid_volume()) / v


def packing(a, kind, K, variant):
    """Compacted packing of --n particles (spheres or K-clumps): dict with hSize rows and particles, from the cache
    folder when there, else made and compacted here (and saved there)."""
    key = '%s%s_n%d_s%d_d%s_f%s_p%s' % (kind, K if kind == 'clump' else '', a.n, a.seed, repr(a.d), repr(a.friction), repr(a.p0))
    path = os.path.join(a.cache, 'packing_%s.json' % key) if a.cache else None
    if path and os.path.exists(path):
        with open(path) as f:
            say(a, variant, 'packing from %s' % path)
            return json.load(f)
    O.reset()
    O.periodic = True
    set_solid_volume(a, kind, K)
    r = a.d / 2
    L0 = (a.n * math.pi * a.d ** 3 / 6 / a.cloud_fraction) ** (1.0 / 3.0)
    sp = pack.SpherePack()
    got = sp.makeCloud((0, 0, 0), (L0, L0, L0), rMean=r, rRelFuzz=0, num=a.n, periodic=True, seed=a.seed)
    if got != a.n:
        raise SystemExit('triaxial.py: makeCloud placed %d of %d spheres at solid fraction %g; lower --cloud-fraction'
                         % (got, a.n, a.cloud_fraction))
    O.cell.setBox(L0, L0, L0)
    mat = O.materials.append(frict_mat(a))
    if kind == 'spheres':
        for c, rad in sp:
            O.bodies.append(utils.sphere(c, rad, material=mat))
    else:
        rng = random.Random(a.seed)
        for c, rad in sp:
            cs, rm = clump_members(c, rad, K, rng)
            O.bodies.appendClumped([utils.sphere(x, rm, material=mat) for x in cs])
    O.engines = engines(a, 0.0, iso_controller(a, a.compact_rate, 'phase_done()'),
                        [PyRunner(iterPeriod=2000, command='progress(%r, "compaction")' % variant)])
    O.dt = a.dt_factor * utils.PWaveTimeStep()
    steps = run_phase(a, variant, 'compaction', 400000)
    h = O.cell.hSize
    out = {'hSize': [[h[i, j] for j in range(3)] for i in range(3)], 'steps': steps, 'kind': kind, 'K': K}
    if kind == 'spheres':
        out['spheres'] = [list(b.state.pos) + [b.shape.radius] for b in O.bodies]
    else:
        out['clumps'] = [[list(O.bodies[i].state.pos) + [O.bodies[i].shape.radius] for i in sorted(b.shape.members.keys())]
                         for b in O.bodies if b.isClump]
    say(a, variant, 'compacted in %d steps' % steps)
    if path:
        os.makedirs(a.cache, exist_ok=True)
        with open(path + '.tmp', 'w') as f:
            json.dump(out, f)
        os.replace(path + '.tmp', path)
    return out


# ------------------------------------------------------------------------------------------------
# shear

ROWS = []


def start_shear():
    """doneHook of the re-consolidation: impose the axial strain (z), keep p0 laterally (x, y)."""
    t = O.cell.trsf
    STATE['trsf0'] = [t[0, 0], t[1, 1], t[2, 2]]
    STATE['shear_start'] = O.iter
    a = STATE['args']
    triax.goal = (-a.p0, -a.p0, math.log(t[2, 2]) - a.eps_max)
    triax.stressMask = 3
    triax.maxStrainRate = (a.lateral_rate * a.rate, a.lateral_rate * a.rate, a.rate)
    triax.doneHook = ''
    STATE['done'] = True
    O.pause()


def record():
    """A curve row (PyRunner after NewtonIntegrator); stops the run at eps_max."""
    if 'trsf0' not in STATE:
        return
    a = STATE['args']
    t = O.cell.trsf
    e = [-(math.log(t[i, i]) - math.log(STATE['trsf0'][i])) for i in range(3)]
    s = utils.getStress()
    s1 = -s[2, 2]
    s3 = -(s[0, 0] + s[1, 1]) / 2.0
    p = (s1 + 2.0 * s3) / 3.0
    q = s1 - s3
    row = (O.iter, e[2], e[0] + e[1] + e[2], e[0], e[1], s1 / 1e3, s3 / 1e3, p / 1e3, q / 1e3, q / p if p else float('nan'),
           (s1 - s3) / (s1 + s3) if (s1 + s3) else float('nan'), porosity(), utils.unbalancedForce(), O.interactions.countReal())
    ROWS.append(row)
    if len(ROWS) % 25 == 0:
        say(a, STATE['variant'], 'shear: eps_a %.3f, q/p %.3f, eps_v %.4f, sig3 %.4g kPa, porosity %.4f'
            % (row[1], row[9], row[2], row[6], row[11]))
    if e[2] >= a.eps_max - 1e-6:
        STATE['done'] = True
        O.pause()


def lsq_slope(xs, ys):
    n = len(xs)
    mx = sum(xs) / n
    my = sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    sxy = sum((x - mx) * (y - my) for x, y in zip(xs, ys))
    return sxy / sxx if sxx > 0 else float('nan')


def metrics(a, rows):
    """Peak and critical-state friction angles, maximum dilatancy angle (definitions: header)."""
    ea = [r[1] for r in rows]
    ev = [r[2] for r in rows]
    sp = [r[10] for r in rows]
    qp = [r[9] for r in rows]
    w = 2
    smooth = [sum(sp[max(0, i - w):i + w + 1]) / len(sp[max(0, i - w):i + w + 1]) for i in range(len(sp))]
    ipk = max(range(len(smooth)), key=lambda i: smooth[i])
    tail = [i for i in range(len(rows)) if ea[i] >= ea[-1] - 0.05]
    s_cv = sum(sp[i] for i in tail) / len(tail)
    qp_cv = sum(qp[i] for i in tail) / len(tail)
    best = (-1e9, 0.0, 0.0)
    for i in range(len(rows)):
        win = [j for j in range(len(rows)) if abs(ea[j] - ea[i]) <= 0.01]
        if len(win) < 5 or ea[i] - 0.01 < ea[0] or ea[i] + 0.01 > ea[-1]:
            continue
        s = lsq_slope([ea[j] for j in win], [ev[j] for j in win])
        psi = math.degrees(math.asin(max(-1.0, min(1.0, -s / (2.0 - s)))))
        if psi > best[0]:
            best = (psi, ea[i], s)
    return {'phi_peak_deg': math.degrees(math.asin(smooth[ipk])), 'eps_a_peak': ea[ipk], 'q_over_p_peak': qp[ipk],
            'phi_cv_deg': math.degrees(math.asin(s_cv)), 'q_over_p_cv': qp_cv, 'psi_max_deg': best[0],
            'eps_a_psi_max': best[1], 'dev_dea_at_psi_max': best[2], 'eps_v_end': ev[-1], 'porosity_end': rows[-1][11]}


def run_variant(a, variant):
    kind, x = variant_kind(variant)
    eta = x if kind == 'spheres' else 0.0
    K = int(x) if kind == 'clump' else 0
    pk = packing(a, kind, K, variant)
    # rebuild at the packed positions, at rest, with the variant's material
    O.reset()
    O.periodic = True
    O.cell.hSize = Matrix3(*[v for row in pk['hSize'] for v in row])
    mat = O.materials.append(roll_mat(a, eta) if eta > 0 else frict_mat(a))
    set_solid_volume(a, kind, K)
    if kind == 'spheres':
        for x, y, z, rad in pk['spheres']:
            O.bodies.append(utils.sphere((x, y, z), rad, material=mat))
    else:
        for members in pk['clumps']:
            O.bodies.appendClumped([utils.sphere((m[0], m[1], m[2]), m[3], material=mat) for m in members])
    STATE.update({'args': a, 'variant': variant})
    STATE.pop('trsf0', None)
    del ROWS[:]
    dt0 = utils.PWaveTimeStep()
    steps_per_row = max(1, int(round(0.001 / (a.rate * a.dt_factor * dt0))))
    O.engines = engines(a, eta, iso_controller(a, a.rate, 'start_shear()'),
                        [PyRunner(iterPeriod=steps_per_row, command='record()', label='recorder'),
                         PyRunner(iterPeriod=5000, command='progress(%r, "consolidation")' % variant, label='triax_progress')])
    O.dt = a.dt_factor * dt0
    n0 = porosity()
    say(a, variant, 'rebuilt: %d bodies, porosity %.4f, dt %.4g s, rate %.4g 1/s (I = %.2g), a row every %d steps'
        % (len(O.bodies), n0, O.dt, a.rate, a.inertial, steps_per_row))
    cons = run_phase(a, variant, 're-consolidation', 400000)
    triax_progress.dead = True
    n_start = porosity()
    say(a, variant, 're-consolidated in %d steps, porosity %.4f; shearing to eps_a = %g' % (cons, n_start, a.eps_max))
    STATE['done'] = False
    limit = 3 * int(a.eps_max / (a.rate * O.dt)) + 10000
    while not STATE['done']:
        if O.iter - STATE['shear_start'] > limit:
            raise SystemExit('triaxial.py: shear of %s did not reach eps_a = %g in %d steps' % (variant, a.eps_max, limit))
        O.run(5000, True)
    if len(ROWS) < 20:
        raise SystemExit('triaxial.py: only %d curve rows for %s; lower --rate or raise --eps-max' % (len(ROWS), variant))
    m = metrics(a, ROWS)
    summary = {'variant': variant, 'kind': kind, 'eta_roll': eta, 'clump_size': K, 'n_particles': a.n,
               'bodies': len(O.bodies), 'seed': a.seed, 'd': a.d, 'young': a.young, 'poisson': a.poisson,
               'friction_deg': a.friction, 'density': a.density, 'damping': a.damping, 'alpha_kr': a.alpha_kr, 'p0': a.p0,
               'eps_max': a.eps_max, 'rate': a.rate, 'inertial_number': a.rate * a.d / math.sqrt(a.p0 / a.density),
               'dt': O.dt, 'steps_compaction': pk['steps'], 'steps_consolidation': cons,
               'steps_shear': O.iter - STATE['shear_start'], 'porosity_0': n_start, 'solid_volume': STATE['solid'],
               'cell_size_0': [pk['hSize'][i][i] for i in range(3)]}
    summary.update(m)
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, '%s.curve.csv' % variant), 'w') as f:
        f.write(','.join(CURVE_COLS) + '\n')
        for r in ROWS:
            f.write('%d,' % r[0] + ','.join('%.17g' % v for v in r[1:13]) + ',%d\n' % r[13])
    with open(os.path.join(a.out, '%s.summary.json' % variant), 'w') as f:
        json.dump(summary, f, indent=1, sort_keys=True)
        f.write('\n')
    say(a, variant, 'done: phi_peak %.2f deg at eps_a %.3f, phi_cv %.2f deg, psi_max %.2f deg, porosity_0 %.4f'
        % (m['phi_peak_deg'], m['eps_a_peak'], m['phi_cv_deg'], m['psi_max_deg'], n_start))
    return summary


args = parse_args(sys.argv[1:])
for v in args.variants:
    run_variant(args, v)
