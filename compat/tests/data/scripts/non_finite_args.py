# NaN or infinity given to a body builder, a body state, a material or an engine (argv[1] picks which)
import sys
from yade import utils
which = sys.argv[1]
if which == 'sphere':
    O.bodies.append(utils.sphere((0, 0, float('nan')), 1))
elif which == 'radius':
    O.bodies.append(utils.sphere((0, 0, 0), float('inf')))
elif which == 'state':
    b = utils.sphere((0, 0, 0), 1)
    b.state.vel = (0, float('nan'), 0)
    O.bodies.append(b)
elif which == 'material':
    O.materials.append(FrictMat(young=float('nan')))
elif which == 'engine':
    O.engines = [ForceResetter(), NewtonIntegrator(gravity=(0, 0, float('nan')))]
elif which == 'live':
    n = NewtonIntegrator()
    O.engines = [n]
    n.gravity = (0, float('inf'), 0)
