# ymport.stl on ASCII and binary STL files (written here: a tetrahedron with shared vertices, a -0.0 that
# merges with 0.0, and coordinates that single precision rounds): every facet's position and vertices.
import os, struct, sys
from yade import ymport

tris = [[(0, 0, 0), (0.1, 0, 0), (0, 0.1, 0)], [(0, 0, 0), (0, 0.1, 0), (0, 0, 0.1)],
        [(-0.0, 0, 0), (0, 0, 0.1), (0.1, 0, 0)], [(0.1, 0, 0), (0, 0, 0.1), (0, 0.1, 0)],
        [(0.3333333, 1.2e-3, 7.123456789), (2.5, -1.75, 3.1), (0.7, 0.9, -4.4)]]
out = sys.argv[1] if len(sys.argv) > 1 else '.'
with open(os.path.join(out, 'ascii.stl'), 'w') as f:
    f.write('solid test\n')
    for t in tris:
        f.write(' facet normal 0 0 1\n  outer loop\n')
        for v in t:
            f.write('   vertex %r %r %r\n' % v)
        f.write('  endloop\n endfacet\n')
    f.write('endsolid test\n')
with open(os.path.join(out, 'binary.stl'), 'wb') as f:
    f.write(b'binary test'.ljust(80, b' ') + struct.pack('<i', len(tris)))
    for t in tris:
        f.write(struct.pack('<12fh', 0, 0, 1, *[c for v in t for c in v], 0))
for tag, name in (('A', 'ascii.stl'), ('B', 'binary.stl')):
    fs = ymport.stl(os.path.join(out, name), scale=2.0, shift=(0.5, 0, -1))
    print('%s %d' % (tag, len(fs)))
    for b in fs:
        print('%s %r %r' % (tag, list(b.state.pos), [list(v) for v in b.shape.vertices]))
    fs = ymport.stl(os.path.join(out, name))
    for b in fs:
        print('%s %r %r %r' % (tag, list(b.state.pos), [list(v) for v in b.shape.vertices], b.state.mass))
