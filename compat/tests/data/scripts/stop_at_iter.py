# O.run(n) sets O.stopAtIter = O.iter + n, a PyRunner may move it, and it is reset to -1 afterwards
import sys
O.engines=[ForceResetter(),NewtonIntegrator()]
O.bodies.append(sphere((0,0,0),1)); O.dt=1e-3
print('A', O.stopAtIter); O.run(10,True); print('B', O.stopAtIter, O.iter)
O.stopAtIter=15; O.run(10,True); print('C', O.stopAtIter, O.iter)
O.engines=O.engines+[PyRunner(command='O.stopAtIter=O.iter+1',iterPeriod=5,nDo=1)]
O.run(10,True); print('D', O.stopAtIter, O.iter); O.run(10,True); print('E', O.stopAtIter, O.iter)
sys.stdout.flush()
