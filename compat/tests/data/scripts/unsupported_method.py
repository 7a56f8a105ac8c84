O.bodies.append([sphere((0, 0, 0), 1), sphere((0, 0, 3), 1)])
O.bodies.erase(1)
