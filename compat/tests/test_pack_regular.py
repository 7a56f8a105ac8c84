"""pack.regularHexa / regularOrtho and the solid predicates (inSphere, inAlignedBox, inCylinder, | & - ^) give
YADE's spheres bit for bit (data/scripts/regular_packs.py prints every centre with repr)."""
from _scripts import needs_compat, needs_yade, tagged_lines


@needs_compat
def test_regular_packs_numbers():
    lines = tagged_lines('ryade', 'regular_packs.py', tags='ABCDEFS')
    counts = {ln.split()[0]: int(ln.split()[1]) for ln in lines if len(ln.split()) == 2}
    # the sphere counts YADE 2023.02a gives (test_regular_packs_as_yade checks every value)
    assert counts == {'A': 72, 'B': 95, 'C': 314, 'D': 72, 'E': 104}
    # the first sphere of A as YADE places it: hcp site (i, j, k) = (0, 1, 2), (a/2) (1, sqrt(3), 4 sqrt(6)/3)
    # with a = 2 r + gap = 0.015 (lower sites are closer than r to a face); mass: density 1000, 4/3 pi r^3
    assert lines[1] == 'A 0.0075 0.012990381056766578 0.024494897427831775 0.007 0.001436755040241732'
    assert abs(0.001436755040241732 - 1000 * 4 / 3. * 3.141592653589793 * 0.007 ** 3) < 1e-18
    assert lines[-1].startswith('S [0.0, 0.02, 0.04, 0.06')


@needs_compat
@needs_yade
def test_regular_packs_as_yade():
    tags = 'ABCDEFS'
    assert tagged_lines('ryade', 'regular_packs.py', tags=tags) == tagged_lines('yade', 'regular_packs.py', tags=tags)
