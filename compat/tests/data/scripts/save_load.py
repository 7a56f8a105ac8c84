# O.save / O.load in one run: a falling pile saved at step 300 and reloaded later continues from the saved
# state (ryade writes a file of its own format; YADE its XML); the bodies are printed at full precision.
import os, sys
out = sys.argv[1] if len(sys.argv) > 1 else '.'
O.bodies.append(utils.wall(0, axis=2))
for i in range(6):
    O.bodies.append(utils.sphere((0.011 * i, 0.003 * (i % 2), 0.012 + 0.02 * i), 0.01))
O.dt = 1e-5
O.run(300, True)
f = os.path.join(out, 'scene.xml.bz2')
O.save(f)

def show(tag):
    for b in O.bodies:
        print('%s %d %d %r %r' % (tag, O.iter, b.id, list(b.state.pos), list(b.state.vel)))

O.run(200, True)
show('A')
O.load(f)
print('B %d %d' % (O.iter, len(O.bodies)))
O.run(200, True)
show('C')
