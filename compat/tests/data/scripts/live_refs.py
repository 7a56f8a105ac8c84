# YADE's reference semantics: vel is live, pos is a copy; script arguments in sys.argv
import sys, json
b = O.bodies[O.bodies.append(sphere((0, 0, 0), 1))]
b.state.vel[2] = 0.1
v = b.state.angVel
v[0] = 5
b.state.pos[1] = 3
b.dynamic = False
json.dump({'vel': list(O.bodies[0].state.vel), 'angVel': list(O.bodies[0].state.angVel),
           'pos': list(O.bodies[0].state.pos), 'blocked': O.bodies[0].state.blockedDOFs, 'argv': sys.argv[1:]},
          open(sys.argv[1], 'w'))
