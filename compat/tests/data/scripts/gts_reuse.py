# PyGTS hands back the Edge / Face that already joins the same vertices / uses the same edges (issue 19:
# clumps/clump-viscoelastic.py's sweptPolylines2gtsSurface of one polyline with both caps)
import gts
from yade import pack
a, b, c = gts.Vertex(0, 0, 0), gts.Vertex(1, 0, 0), gts.Vertex(0, 1, 0)
e1 = gts.Edge(a, b)
print('A', e1 is gts.Edge(a, b), e1 is gts.Edge(b, a), gts.Segment(a, c) is gts.Segment(c, a))
e2, e3 = gts.Edge(b, c), gts.Edge(c, a)
f1 = gts.Face(e1, e2, e3)
print('B', f1 is gts.Face(e1, e2, e3), f1 is gts.Face(e3, e1, e2), f1 is gts.Face(a, b, c), f1 is gts.Triangle(a, b, c))
s = gts.Surface()
for f in (f1, gts.Face(e2, e3, e1), gts.Face(a, c, b)):
    s.add(f)
print('C', len(s.faces()))
line = [Vector3(-.5, -.5, -.5), Vector3(.5, -.5, -.5), Vector3(.5, 1.5, -.5), Vector3(-.5, 1.5, -.5)]
print('D', len(pack.sweptPolylines2gtsSurface([line], capStart=True, capEnd=True).faces()),
      len(pack.sweptPolylines2gtsSurface([line, [p + Vector3(0, 0, 1) for p in line]], capStart=True, capEnd=True).faces()))
