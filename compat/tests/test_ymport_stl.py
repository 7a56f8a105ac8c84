"""ymport.stl (YADE's STLImporter + py/ymport.py): ASCII and binary files give YADE's facets bit for bit; so does
ymport.gmsh on a .mesh file."""

from _scripts import needs_compat, needs_yade, tagged_lines, tagged_lines_both


@needs_compat
def test_stl_numbers(tmp_path):
    lines = tagged_lines('ryade', 'stl_import.py', args=[str(tmp_path)], tags='AB')
    assert lines.count('A 5') == 1 and lines.count('B 5') == 1 and len(lines) == 22
    # the first facet of the tetrahedron (0,0,0), (0.1,0,0), (0,0.1,0) unscaled: incircle centre of the
    # right triangle with legs a = 0.1 (single precision), r = a (2 - sqrt 2) / 2, so both coordinates equal r
    # (lines: 'A 5', five facets scaled by 2 and shifted by (0.5, 0, -1), then the five unscaled)
    pos = [float(x) for x in lines[6].split('[')[1].split(']')[0].split(',')]
    a = 0.10000000149011612
    r = a * (2 - 2 ** 0.5) / 2
    assert abs(pos[0] - r) < 1e-15 and pos[0] == pos[1] and pos[2] == 0
    scaled = [float(x) for x in lines[1].split('[')[1].split(']')[0].split(',')]
    assert scaled == [pos[0] * 2 + 0.5, pos[1] * 2, -1.0]
    # ASCII and binary: the same single-precision coordinates, hence the same facets
    assert [ln[1:] for ln in lines if ln[0] == 'A'] == [ln[1:] for ln in lines if ln[0] == 'B']


@needs_compat
@needs_yade
def test_stl_as_yade(tmp_path):
    ryade, yade = tagged_lines_both('stl_import.py', tmp_path, 'AB')
    assert ryade == yade


@needs_compat
def test_gmsh_numbers(tmp_path):
    lines = tagged_lines('ryade', 'gmsh_import.py', args=[str(tmp_path)], tags='M')
    assert lines[0] == 'M 4' and lines[5] == 'M 4' and len(lines) == 10
    # the first triangle (0,0,0), (1.5,0,0), (0.7,0.6,0.9) unscaled: its incircle centre lies in its plane
    # y = 2/3 z (the plane through the x axis and the apex)
    pos = [float(x) for x in lines[1].split('[')[1].split(']')[0].split(',')]
    assert abs(pos[1] - pos[2] * 0.6 / 0.9) < 1e-15 and 0 < pos[0] < 1.5


@needs_compat
@needs_yade
def test_gmsh_as_yade(tmp_path):
    ryade, yade = tagged_lines_both('gmsh_import.py', tmp_path, 'M')
    assert ryade == yade
