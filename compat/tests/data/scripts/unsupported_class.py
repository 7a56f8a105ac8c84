# a YADE script using a class ryade does not implement (line 4)
O.bodies.append(sphere((0, 0, 0), 1))
print('before')
O.engines = [ForceResetter(), HydroForceEngine(densFluid=1000)]
print('never printed')
