# run by execfile_main.py through execfile
O.bodies.append([sphere((0, 0, 0), r), sphere((0, 0, 3 * r), r / 2)])
volume = sum(4 / 3. * pi * b.shape.radius ** 3 for b in O.bodies)
