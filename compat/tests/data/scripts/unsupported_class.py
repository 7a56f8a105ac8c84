# a YADE script using a class ryade does not implement (line 4)
O.bodies.append(sphere((0, 0, 0), 1))
print('before')
O.engines = [ForceResetter(), FlowEngine()]
print('never printed')
