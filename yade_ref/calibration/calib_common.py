# Shared helpers for the geogrid calibration tests (tensile.py, cantilever.py).
# Plain YADE 2023.02a (`yade -n -x`, one thread). Imported through sys.argv[0]'s folder because
# __file__ is /usr/bin/yade under `yade -x`.
#
# Rib model (grid-pid-api.md 1.8-1.12, study.md "Geogrid ribs"): gridNode + gridConnection, nodes
# CohFrictMat(momentRotationLaw=True, normalCohesion = shearCohesion = 1e100), law
# Law2_ScGeom6D_CohFrictPhys_CohesionMoment. gridConnection() sets per bond (L = bond length)
#   kn = E pi r^2 / L, ks = 12 E I / L^3, kr = E I / L, ktw = 2 I G / L,  I = pi (2r)^4 / 64, G = E / (2(1+nu)),
# and the calibration multiplies these by kn_scale, ks_scale, kr_scale, ktw_scale (per interaction,
# right after gridConnection(); the Ip2 never touches the stiffness again).
import json, math, sys
from yade import *
from yade.gridpfacet import gridNode, gridConnection

# Parameters shared by both tests (the study's rib, study.md "Geogrid ribs").
COMMON_DEFAULTS = {
    "a": 0.06,            # rib length (junction to junction) [m]
    "r": 0.002,           # rib (and node) radius [m]
    "E": 1e9,             # Young's modulus of the node material [Pa]
    "nu": 0.3,            # Poisson's ratio (enters G for ktw)
    "rho": 950.0,         # density [kg/m^3] (node mass = half-connection volumes * rho)
    "cohesion": 1e100,    # normalCohesion = shearCohesion: bonds never yield nor break
    "kn_scale": 1.0, "ks_scale": 1.0, "kr_scale": 1.0, "ktw_scale": 1.0,
    "damping": 0.0,       # NewtonIntegrator local (non-viscous) damping
    "dt_factor": 0.5,     # dt = dt_factor * min over free nodes of 2 sqrt(m/sum kn), 2 sqrt(I/sum max(kr,ktw))
}


def parse_params(defaults, argv=None):
    """argv[1] may be a JSON file (object of parameters); any further `key=value` arguments override.
    Values of `key=value` are parsed as JSON when possible (numbers, true/false, lists), else kept as strings."""
    argv = sys.argv[1:] if argv is None else argv
    p = dict(defaults)
    for arg in argv:
        if '=' in arg:
            k, v = arg.split('=', 1)
            try:
                v = json.loads(v)
            except ValueError:
                pass
            src = {k: v}
        elif arg.endswith('.json'):
            with open(arg) as f:
                src = json.load(f)
        else:
            raise SystemExit('unrecognised argument %r (expected params.json or key=value)' % arg)
        for k, v in src.items():
            if k not in p:
                raise SystemExit('unknown parameter %r; known: %s' % (k, ', '.join(sorted(p))))
            p[k] = v
    return p


def setup_scene(p, gravity=(0, 0, 0), extra_engines=()):
    """Fresh scene with the grid materials and the bond-only engine list (no collider: these tests have
    no external contacts, and the ribs of one flat strip never come near each other). Returns the node material id."""
    O.reset()
    mat = O.materials.append(CohFrictMat(young=p["E"], poisson=p["nu"], density=p["rho"],
                                         frictionAngle=math.radians(30),
                                         normalCohesion=p["cohesion"], shearCohesion=p["cohesion"],
                                         momentRotationLaw=True, label='gridnode'))
    O.engines = [
        ForceResetter(),
        InteractionLoop([Ig2_GridNode_GridNode_GridNodeGeom6D()],
                        [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True, setCohesionOnNewContacts=False)],
                        [Law2_ScGeom6D_CohFrictPhys_CohesionMoment()]),
    ] + list(extra_engines) + [
        NewtonIntegrator(damping=p["damping"], gravity=gravity, label='newton'),
    ]
    return mat


def connect(id1, id2, p, mat):
    """gridConnection (after O.engines is set) + stiffness scale factors. Returns the connection body id."""
    c = gridConnection(id1, id2, p["r"], material=mat)
    ph = O.interactions[id1, id2].phys
    ph.kn *= p["kn_scale"]
    ph.ks *= p["ks_scale"]
    ph.kr *= p["kr_scale"]
    ph.ktw *= p["ktw_scale"]
    return c


def bond_defaults(p, L):
    """gridConnection's stiffnesses for a bond of length L (unscaled)."""
    r, E = p["r"], p["E"]
    I = math.pi * (2 * r) ** 4 / 64
    G = E / (2 * (1 + p["nu"]))
    return {"kn": E * math.pi * r ** 2 / L, "ks": 12 * E * I / L ** 3, "kr": E * I / L, "ktw": 2 * I * G / L}


def critical_dt():
    """Mass-spring estimate over the free grid nodes (utils.PWaveTimeStep() is useless with grids,
    grid-pid-api.md 1.13-3): translational 2 sqrt(m / sum kn), rotational 2 sqrt(I / sum max(kr, ktw))."""
    dtc = float('inf')
    for b in O.bodies:
        if not isinstance(b.shape, GridNode) or b.state.blockedDOFs == 'xyzXYZ':
            continue
        K = Kr = 0.0
        for i in O.interactions.withBody(b.id):
            if isinstance(i.phys, CohFrictPhys):
                K += i.phys.kn
                Kr += max(i.phys.kr, i.phys.ktw)
        dtc = min(dtc, 2 * math.sqrt(b.state.mass / K), 2 * math.sqrt(b.state.inertia[0] / Kr))
    return dtc


def count_bonds():
    return sum(1 for i in O.interactions if isinstance(i.phys, CohFrictPhys))


def write_json(path, obj):
    with open(path, 'w') as f:
        json.dump(obj, f, indent=1, sort_keys=False)
        f.write('\n')
