# pack.regularHexa / regularOrtho inside YADE's solid predicates (and their combinations): every sphere's
# centre and radius with full precision, in creation order, and the predicates' boxes.
from yade import pack

def show(tag, spheres):
    print('%s %d' % (tag, len(spheres)))
    for s in spheres:
        p = s.state.pos
        print('%s %r %r %r %r %r' % (tag, p[0], p[1], p[2], s.shape.radius, s.state.mass))

box = pack.inAlignedBox((0, 0, 0), (0.1, 0.07, 0.05))
cyl = pack.inCylinder((0.02, 0.03, -0.01), (0.05, 0.01, 0.09), 0.031)
ball = pack.inSphere((0.03, 0.02, 0.01), 0.035)
show('A', pack.regularHexa(box, radius=0.007, gap=0.001))
show('B', pack.regularOrtho(cyl, radius=0.0061, gap=0.0003))
show('C', pack.regularHexa(ball - pack.inSphere((0.03, 0.02, 0.0), 0.01), radius=0.004, gap=0.0))
show('D', pack.regularOrtho((box & ball) | pack.inSphere((0.1, 0.1, 0.1), 0.012), radius=0.005, gap=0.0002))
show('E', regularHexa(cyl ^ ball, 0.006, 0.0005))
for t, p in (('F', cyl), ('F', box | ball), ('F', box & cyl)):
    mn, mx = p.aabb()
    print('%s %r %r %r %r %r %r' % (t, mn[0], mn[1], mn[2], mx[0], mx[1], mx[2]))
    print('%s %r %r' % (t, list(p.center()), list(p.dim())))
print('S %r' % [float(x) for x in arange(0, 0.3, 0.3 / 15.)])
