"""The gts stand-in hands back the Edge / Face that already joins the same vertices / uses the same edges,
as PyGTS does (issue 19: clumps/clump-viscoelastic.py's one-polyline surface capped at both ends made 4
facets instead of YADE's 2). YADE_LINES: data/scripts/gts_reuse.py under Debian's YADE 2023.02a."""
from _scripts import needs_compat, needs_yade, tagged_lines

YADE_LINES = ['A True True True', 'B True True True True', 'C 1', 'D 2 10']


@needs_compat
def test_gts_reuse_equals_yade():
    assert tagged_lines('ryade', 'gts_reuse.py', tags='ABCD') == YADE_LINES


@needs_compat
@needs_yade
def test_gts_reuse_live_yade():
    assert tagged_lines('yade', 'gts_reuse.py', tags='ABCD') == YADE_LINES
