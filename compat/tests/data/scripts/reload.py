# O.reload loads again the scene last saved or loaded (O.filename): after O.saveTmp it is ':memory:', after
# O.save the file; the bodies after reloading and running again equal those of the first run.
import os, sys
out = sys.argv[1] if len(sys.argv) > 1 else '.'
print('R %r' % (O.filename,))
O.bodies.append(utils.wall(0, axis=2))
for i in range(3):
    O.bodies.append(utils.sphere((0.005 * i, 0, 0.011 + 0.021 * i), 0.01))
O.dt = 1e-5
O.saveTmp()
print('R %r' % (O.filename,))
O.run(400, True)
first = [list(b.state.pos) for b in O.bodies]
O.reload()
print('R %d %r' % (O.iter, O.filename))
O.run(400, True)
print('R %r' % ([list(b.state.pos) for b in O.bodies] == first))
f = os.path.join(out, 'r.xml')
O.save(f)
O.run(100, True)
O.reload()
print('R %d %r %r' % (O.iter, os.path.basename(O.filename), [list(b.state.vel) for b in O.bodies][1]))
