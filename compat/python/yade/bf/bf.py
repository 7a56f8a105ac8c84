"""The clump breakage algorithm of YADE's py/bf/bf.py (Brzezinski, K. & Gladkyy, A. (2022), Clump breakage
algorithm for DEM simulation of crushable aggregates; strength criterion of Gladkyy, A. & Kuna, M.
(2017), Granular Matter 19(3), 41), with YADE's arithmetic.

YADE accumulates the stress tensor in a numpy float32 array under numpy 1.24's casting rules (Debian's
python3-numpy): a float64 term added to a float32 element is summed in float64 and rounded to float32
on store, and a float64 scalar divides a float32 array in float32. ryade's Python may carry another
numpy (2.x changed these rules, NEP 50), so the roundings are written out here instead of left to
numpy's promotion.
"""

import numpy as np

# absolute imports: scripts load this package as the top-level `bf` too
from yade import math, pack
from yade._core import Omega, Sphere
from yade.utils import growParticle, sphere

__all__ = ['stressTensor', 'checkFailure', 'replaceSphere', 'evalClump']

_F32 = np.float32


def _O():
    return Omega()


def _add_outer(sigma, force, arm):
    """sigma[i, j] += force[i] * arm[j], each element kept in float32 as numpy 1.24 does (the product
    in the operands' precision, the sum in float64 when either side is float64, then rounded)."""
    for i in range(3):
        for j in range(3):
            p = force[i] * arm[j]
            if isinstance(p, np.float32):
                sigma[i, j] = sigma[i, j] + p  # float32 + float32, in float32
            else:
                sigma[i, j] = _F32(float(sigma[i, j]) + float(p))


def _contact_force(intr, center):
    """(force, arm) of one contact as bf.stressTensor takes it: the normal and shear forces, each scaled
    by the cosine between the branch vector (contact point - center) and -normal."""
    arm = intr.geom.contactPoint - center
    cosine = np.dot(arm / np.linalg.norm(arm), -intr.geom.normal)
    shear = intr.phys.shearForce * cosine
    normal = intr.phys.normalForce * cosine
    return shear + normal, shear, arm


def stressTensor(b, stress_correction=True):
    """bf.stressTensor: the Love-Weber stress of sphere `b` from its contacts (contacts with members of
    its own clump skipped), closed by two fictitious contacts at +-radius along the unbalanced force
    when `stress_correction`, divided by the sphere's volume; a 3x3 float32 array."""
    O = _O()
    center = b.state.pos
    radius = b.shape.radius
    volume = (np.pi * radius ** 3) * 4 / 3
    sigma = np.zeros([3, 3]).astype(_F32)
    if b.isStandalone:
        f_u, t_u = O.forces.f(b.id), O.forces.t(b.id)
        for intr in b.intrs():
            ff, _, arm = _contact_force(intr, center)
            _add_outer(sigma, ff, arm)
    else:
        cid = b.clumpId
        f_u = np.zeros(3).astype(_F32)
        t_u = np.zeros(3).astype(_F32)
        for intr in b.intrs():
            other = intr.id2 if intr.id1 == b.id else intr.id1
            if O.bodies[other].clumpId == cid:
                continue
            ff, shear, arm = _contact_force(intr, center)
            f_u += np.asarray(ff, dtype=float)
            t_u += np.cross(arm, shear)
            _add_outer(sigma, ff, arm)
    if stress_correction and np.linalg.norm(f_u) > 0:
        # two fictitious contacts: at +radius n the opposite of the unbalanced force plus the torque's
        # couple force, at -radius n the couple's other force (n = unbalanced force direction)
        n = f_u / np.linalg.norm(f_u)
        couple1 = np.cross(0.5 * t_u, n) / radius
        couple2 = np.cross(0.5 * t_u, -1 * n) / radius
        for arm, ff in ((radius * n, (-1 * f_u) + couple1), (-1 * radius * n, couple2)):
            _add_outer(sigma, ff, arm)
    # float32 array / Python float: float32 division (numpy 1.24 and 2 agree here)
    return sigma / volume


def checkFailure(b, tension_strength, compressive_strength, wei_V0=0.01, wei_P=0.63, wei_m=3, weibull=True,
                 stress_correction=True):
    """bf.checkFailure: the effort (equivalent stress / strength) of sphere `b` by the Mohr-Coulomb-Weibull
    criterion of Gladkyy & Kuna (2017) when the strength is exceeded, else 0."""
    sigma = stressTensor(b, stress_correction=stress_correction)
    if weibull:
        # the Weibull size effect divides the stress (the paper's multiplication applies to the strength)
        V = (np.pi * b.shape.radius ** 3) * 4 / 3
        coeff = ((-wei_V0 / V) * np.log(1 - wei_P)) ** (1 / wei_m)
        sigma = sigma / _F32(coeff)  # numpy 1.24: a float64 scalar divides a float32 array in float32
    # float32 eigenvalues; numpy 1.24 takes a float32 scalar op a Python number in float64
    s1, _, s3 = (float(x) for x in np.sort(math.eig(sigma)[0])[::-1])
    s_tau = s1 - s3 * tension_strength / compressive_strength
    if s1 < 0 and s3 < 0 and s3 < -compressive_strength:  # (a) compression
        return -s3 / compressive_strength
    if s1 > 0 and s3 > 0 and s1 > tension_strength:  # (b) tension
        return s1 / tension_strength
    if abs(s_tau) > abs(tension_strength):  # (c) Mohr-Coulomb
        return abs(s_tau) / abs(tension_strength)
    return 0


def replaceSphere(sphere_id, subparticles_mass=None, radius_ratio=2, relative_gap=0, neighbours_ids=[],
                  initial_packing_scale=1.5, max_scale=3, scale_multiplier=None, search_for_neighbours=True,
                  outer_predicate=None, grow_radius=1., max_grow_radius=2.0):
    """bf.replaceSphere: erase sphere `sphere_id` and fill its place with radius_ratio**3 (times the mass
    fraction) subparticles from a hexagonal packing, avoiding the neighbour spheres; returns None, or the
    sphere's id when no packing up to `max_scale` holds enough subparticles (the sphere is kept)."""
    O = _O()
    assert grow_radius <= max_grow_radius
    body = O.bodies[sphere_id]
    r, center, full_mass = body.shape.radius, body.state.pos, body.state.mass
    if subparticles_mass is None:
        subparticles_mass = full_mass
    if subparticles_mass == 0:
        print("Sphere (id={:d}) was erased without replacing with subparticles. The change of the mass is negligible "
              "(the updated mass of the clump has not changed). For grater accuracy increase the 'discretization' "
              "parameter.".format(sphere_id))
        O.bodies.erase(sphere_id)
        return None
    if scale_multiplier is None:
        scale_multiplier = max_scale / initial_packing_scale
    n_req = int(np.ceil(radius_ratio ** 3 * subparticles_mass / full_mass))
    mat = body.material
    sub_r = ((3 * (subparticles_mass / n_req)) / (4 * np.pi * mat.density)) ** (1 / 3)
    if search_for_neighbours:
        found = set(neighbours_ids)
        for other in O.bodies:
            if other.id != sphere_id and isinstance(other.shape, Sphere):
                d = ((np.array(center) - np.array(other.state.pos)) ** 2).sum() ** 0.5
                if d < r * max_scale + other.shape.radius:
                    found.add(other.id)
        neighbours_ids = list(found)
    while True:
        region = pack.inSphere(center, r * initial_packing_scale)
        for nid in neighbours_ids:
            nb = O.bodies[nid]
            region = region - pack.inSphere(nb.state.pos, nb.shape.radius)
        if outer_predicate is not None:
            region = region & outer_predicate
        sp = pack.regularHexa(region, radius=sub_r / grow_radius, gap=relative_gap * sub_r, material=mat)
        if len(sp) >= n_req:
            break
        initial_packing_scale *= scale_multiplier
        if initial_packing_scale > max_scale:
            print("We will NOT crash the particle with id id={:d}. ).".format(body.id))
            return body.id
    # keep the n_req subparticles nearest the center (a stable sort, as YADE's sorted())
    by_distance = sorted(((s, (np.array(s.state.pos - center) ** 2).sum()) for s in sp), key=lambda x: x[1])
    for s, _ in by_distance[:n_req]:
        growParticle(O.bodies.append(s), grow_radius)
    O.bodies.erase(sphere_id)
    return None


def evalClump(clump_id, radius_ratio, tension_strength, compressive_strength, relative_gap=0, wei_V0=0.001,
              wei_P=0.63, wei_m=3, weibull=True, stress_correction=True, initial_packing_scale=1.5, max_scale=3,
              search_for_neighbours=True, outer_predicate=None, discretization=20, grow_radius=1.,
              max_grow_radius=2.0):
    """bf.evalClump: check every member of clump `clump_id`; the member with the largest effort >= 1 is
    replaced by subparticles (released from the clump first) and the clump is split into its connected
    parts. True when the clump broke."""
    O = _O()
    clump = O.bodies[clump_id]
    members = clump.shape.members.keys()
    clump_mass = clump.state.mass
    max_effort, to_break = 0, -1
    for mid in members:
        effort = checkFailure(b=O.bodies[mid], tension_strength=tension_strength,
                              compressive_strength=compressive_strength, wei_V0=wei_V0, wei_P=wei_P, wei_m=wei_m,
                              weibull=weibull, stress_correction=stress_correction)
        if effort > max_effort:
            max_effort = effort
            if effort >= 1:
                to_break = mid
    if max_effort < 1:
        return False
    replace = dict(radius_ratio=radius_ratio, relative_gap=relative_gap, initial_packing_scale=initial_packing_scale,
                   max_scale=max_scale, search_for_neighbours=search_for_neighbours, outer_predicate=outer_predicate,
                   max_grow_radius=max_grow_radius, grow_radius=grow_radius)
    if len(members) == 2:
        kept_mass = [O.bodies[m].state.mass for m in members if m != to_break][-1]
        if replaceSphere(to_break, subparticles_mass=clump_mass - kept_mass, **replace) is not None:
            return False
        O.bodies.erase(clump_id)
    if len(members) > 2:
        O.bodies.releaseFromClump(to_break, clump_id, discretization=discretization)
        kept_mass = O.bodies[clump_id].state.mass
        if replaceSphere(to_break, subparticles_mass=clump_mass - kept_mass, **replace) is not None:
            O.bodies.addToClump([to_break], clump_id, discretization=discretization)
            return False
        _split_clump(clump_id, discretization)
    return True


def _split_clump(clump_id, discretization):
    """The rest of bf.evalClump: group the clump's members into sets of mutually overlapping spheres
    (YADE's pairwise union until no two sets intersect), then rebuild every group as a standalone sphere
    or a new clump and erase the old clump when any group was found."""
    O = _O()
    ids = O.bodies[clump_id].shape.members.keys()
    groups = []
    for m1 in ids:
        g = {m1}
        for m2 in ids:
            r1, r2 = O.bodies[m1].shape.radius, O.bodies[m2].shape.radius
            p1, p2 = np.array(O.bodies[m1].state.pos), np.array(O.bodies[m2].state.pos)
            if ((p1 - p2) ** 2).sum() ** 0.5 < r1 + r2:
                g.add(m2)
        groups.append(g)
    merged = True
    while merged:
        merged = False
        for i in range(len(groups) - 1):
            for j in range(i + 1, len(groups)):
                if groups[i] & groups[j]:
                    groups[i] = groups[i] | groups[j]
                    groups[j].clear()
                    merged = True
    # YADE's flag is set by any non-empty group (its index test is always true)
    erase = False
    for g in groups:
        if not g:
            continue
        erase = True
        copies = []
        for mid in list(g):
            m = O.bodies[mid]
            copies.append(sphere(m.state.pos, m.shape.radius, material=m.material))
            if len(g) > 1:
                O.bodies.erase(mid)
        if len(g) == 1:
            O.bodies.append(copies[0])
            O.bodies.erase(list(g)[0])
        else:
            O.bodies.appendClumped(copies, discretization=discretization)
    if erase:
        O.bodies.erase(clump_id)
