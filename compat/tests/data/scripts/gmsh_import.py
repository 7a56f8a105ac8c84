# ymport.gmsh on a small MEDIT .mesh file (written here): every facet's position and vertices, plain and
# scaled, rotated and shifted.
import os, sys
from yade import ymport
out = sys.argv[1] if len(sys.argv) > 1 else '.'
f = os.path.join(out, 'pyramid.mesh')
with open(f, 'w') as m:
    # (no blank lines: YADE's reader, like ours, takes the first word of every line it searches)
    m.write('MeshVersionFormatted 1\nDimension\n3\nVertices\n5\n0 0 0 1\n1.5 0 0 1\n1.5 1.25 0 1\n0 1.25 0 1\n'
            '0.7 0.6 0.9 2\nTriangles\n4\n1 2 5 1\n2 3 5 1\n3 4 5 1\n4 1 5 1\nEnd\n')
for kw in ({}, dict(scale=0.001, shift=(0.1, -0.2, 0.3), orientation=Quaternion((1, 1, 0), 0.3), color=(1, 0, 0))):
    fs = ymport.gmsh(f, **kw)
    print('M %d' % len(fs))
    for b in fs:
        print('M %r %r' % (list(b.state.pos), [list(v) for v in b.shape.vertices]))
