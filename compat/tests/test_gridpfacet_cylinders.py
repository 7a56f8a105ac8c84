"""gridpfacet.cylinder / cylinderConnection build YADE's nodes and connections (ids, masses, inertias) and the
chain then moves as in YADE, bit for bit."""
from _scripts import needs_compat, needs_yade, tagged_lines


@needs_compat
def test_cylinders_numbers():
    lines = tagged_lines('ryade', 'grid_cylinders.py', tags='G')
    # YADE's order: a cylinder's two nodes then its connection; a chain's nodes first, then its connections
    assert lines[0] == 'G [0, 1, 3, 4, 5, 6] [2, 7, 8, 9]'
    # a node carries half of its connection's mass: pi r^2 L rho / 2 (r 0.1, L 1, density 1000)
    assert lines[1] == 'G 0 GridNode [0.0, 0.0, 0.0] 15.707963267948967 [0.06283185307179588, 0.06283185307179588, 0.06283185307179588]'
    assert abs(15.707963267948967 - 3.141592653589793 * 0.1 ** 2 * 1.0 * 1000 / 2) < 1e-12
    assert len(lines) == 21


@needs_compat
@needs_yade
def test_cylinders_as_yade():
    assert tagged_lines('ryade', 'grid_cylinders.py', tags='G') == tagged_lines('yade', 'grid_cylinders.py', tags='G')
