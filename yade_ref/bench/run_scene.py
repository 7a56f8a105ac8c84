# Load a ryade scene file (golden/FORMAT.md) into YADE exactly (17-digit state, mass and inertia as
# stored) and time N steps:   yade -n -x yade_ref/bench/run_scene.py SCENE.json STEPS [WARMUP]
# Prints one line: "BENCH steps=N bodies=B seconds=S particle_steps_per_s=... contact_updates_per_s=..."
import json, sys, time

path, steps = sys.argv[1], int(sys.argv[2])
warmup = int(sys.argv[3]) if len(sys.argv) > 3 else 0
d = json.load(open(path))
O.periodic = bool(d['periodic'])
if O.periodic:
    h = d['cell_hsize']
    O.cell.hSize = Matrix3(*[h[i][j] for i in range(3) for j in range(3)])
mats = {}


def material(m):
    key = json.dumps(m, sort_keys=True)
    if key not in mats:
        mm = FrictMat(young=m['young'], poisson=m['poisson'], frictionAngle=m['frictionAngle'], density=m['density'],
                      label=m.get('label', ''))
        if m['id'] >= 0:
            O.materials.append(mm)
        mats[key] = mm
    return mats[key]


for b in d['bodies']:
    s = b['shape']
    body = Body()
    if s['class'] == 'Sphere':
        body.shape = Sphere(radius=s['radius'])
    elif s['class'] == 'Box':
        body.shape = Box(extents=Vector3(*s['extents']))
    elif s['class'] == 'Facet':
        body.shape = Facet(vertices=[Vector3(*v) for v in s['vertices']])
    elif s['class'] == 'Wall':
        body.shape = Wall(axis=s['axis'], sense=s['sense'])
    else:
        raise RuntimeError('shape %s not supported by run_scene.py' % s['class'])
    body.material = material(b['material'])
    st = body.state
    st.pos, st.vel, st.angVel = Vector3(*b['pos']), Vector3(*b['vel']), Vector3(*b['angVel'])
    w, x, y, z = b['ori']
    st.ori = Quaternion(w, x, y, z)
    st.mass, st.inertia = b['mass'], Vector3(*b['inertia'])
    st.blockedDOFs = ''.join(c for c, bit in zip('xyzXYZ', (1, 2, 4, 8, 16, 32)) if b['blockedDOFs'] & bit)
    st.isDamped = b['isDamped']
    body.mask = b['mask']
    body.bounded = b['bounded']
    O.bodies.append(body)

engines = []
for e in d['engines']:
    c = e['class']
    if c == 'ForceResetter':
        engines.append(ForceResetter())
    elif c == 'InsertionSortCollider':
        bo = [eval(f['class'])() for f in e['bounds']]
        engines.append(InsertionSortCollider(bo, verletDist=e['verletDist'], allowBiggerThanPeriod=e['allowBiggerThanPeriod']))
    elif c == 'InteractionLoop':
        engines.append(InteractionLoop([eval(f['class'])() for f in e['geom']], [eval(f['class'])() for f in e['phys']],
                                       [eval(f['class'])() for f in e['law']]))
    elif c == 'NewtonIntegrator':
        engines.append(NewtonIntegrator(damping=e['damping'], gravity=Vector3(*e['gravity']), dampGravity=e['dampGravity']))
    else:
        raise RuntimeError('engine %s not supported by run_scene.py' % c)
O.engines = engines
O.dt = d['dt']
if warmup:
    O.run(warmup, True)
t0 = time.time()
O.run(steps, True)
dt = time.time() - t0
nc = O.interactions.countReal()
print('BENCH steps=%d bodies=%d contacts=%d seconds=%.6f particle_steps_per_s=%.6g contact_updates_per_s=%.6g'
      % (steps, len(O.bodies), nc, dt, steps * len(O.bodies) / dt, steps * nc / dt))
sys.stdout.flush()
