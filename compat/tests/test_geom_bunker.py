"""geom.facetBunker and facetCone give YADE's facets bit for bit (py/geom.py)."""
from _scripts import needs_compat, needs_yade, tagged_lines


@needs_compat
def test_bunker_numbers():
    lines = tagged_lines('ryade', 'facet_bunker.py', tags='K')
    counts = [int(ln.split()[1]) for ln in lines if len(ln.split()) == 2]
    # 10 segments, wallMask 4: pipe, cone and bunker sides, 20 each; 7 segments, wallMask 7, hPipe 0: a pipe of
    # height 0 (wallMask & 2 asks for one) is its top disc, 7, + cone side 14 + bunker top 7 and side 14;
    # 10 segments, wallMask 6, no bunker: pipe bottom 10 and side 20 + cone side 20; the cone alone, 5
    # segments: top 5, bottom 5, side 10
    assert counts == [60, 42, 50, 20]
    # the first facet of the first bunker: mask 5, identity orientation, on the pipe of radius 0.1 about
    # (0, 1.5, -0.7 + 0.05)
    first = lines[1]
    assert first.endswith(' 5') and '[0.0, 0.0, 0.0, 1.0]' in first


@needs_compat
@needs_yade
def test_bunker_as_yade():
    assert tagged_lines('ryade', 'facet_bunker.py', tags='K') == tagged_lines('yade', 'facet_bunker.py', tags='K')
