# RyadePistonController.boxPorosity (a ryade extension) against the study script's own Python
# box_porosity (yade_ref/study/study.py, its porosity functions read from the file and run here as
# they are): random spheres in a periodic cell, many cut by the box's faces, edges and corners, some
# reaching the box through their periodic images, boxes of several heights. Prints one line per box:
# "B <python repr> <native repr>", then one line per single sphere ("S ..."). Usage: compat run porosity_native.py STUDY_PY
import math, random, sys

src = open(sys.argv[1]).read()
start = src.index('# exact sphere / box intersection volume')
end = src.index('# scene\n')
ns = {'math': math}
exec(src[start:end], ns)

rng = random.Random(5)
Lx, Ly = 0.3, 0.31
O.periodic = True
O.cell.setBox(Lx, Ly, 1.0)
ids = []
for k in range(600):
    r = rng.uniform(0.008, 0.022)
    c = (rng.uniform(-0.05, Lx + 0.05), rng.uniform(-0.05, Ly + 0.05), rng.uniform(0.0, 0.4))
    ids.append(O.bodies.append(utils.sphere(c, r)))
pc = RyadePistonController(ids=[ids[0]])
O.engines = [pc]
for zlo, zhi, half in ((0.0, 0.3, 0.075), (0.05, 0.21, 0.149), (0.1, 0.102, 0.02), (-1, 2, 0.16)):
    lo = (Lx / 2 - half, Ly / 2 - half, zlo)
    hi = (Lx / 2 + half, Ly / 2 + half, zhi)
    sph = [(O.bodies[i].state.pos, O.bodies[i].shape.radius) for i in ids]
    py = ns['box_porosity'](sph, lo, hi, Lx, Ly)
    native = pc.boxPorosity(ids, lo, hi, Lx, Ly, ns['GL_X'], ns['GL_W'])
    print('B %r %r' % (py, native))
# one sphere in a box about its size, cut by faces, edges and corners (the box's volume of the
# order of the sphere's, so that one ulp of its volume shows in the porosity); boxes across the
# cell's sides reach the sphere through an image
for i in ids[:300]:
    c, r = O.bodies[i].state.pos, O.bodies[i].shape.radius
    lo = tuple(c[a] + rng.uniform(-1.3, 0.6) * r for a in range(3))
    hi = tuple(lo[a] + rng.uniform(0.3, 2.2) * r for a in range(3))
    py = ns['box_porosity']([(c, r)], lo, hi, Lx, Ly)
    native = pc.boxPorosity([i], lo, hi, Lx, Ly, ns['GL_X'], ns['GL_W'])
    print('S %r %r' % (py, native))
try:
    pc.boxPorosity([ids[0], 10**6], lo, hi, Lx, Ly, ns['GL_X'], ns['GL_W'])
except ValueError as e:
    print('E %s' % e)
