# geom.facetBunker / facetCone: every facet's position, orientation, vertices and mask, in creation order.
from yade import geom
for kw in [dict(center=[0, 1.5, -0.7], dBunker=1.1, dOutput=0.2, hBunker=0.2, hOutput=0.2, hPipe=0.1, mask=5),
           dict(center=(0.1, 0.2, 0.3), dBunker=0.5, dOutput=0.1, hBunker=0.3, hOutput=0.15, wallMask=7, segmentsNumber=7,
                orientation=Quaternion((1, 0, 1), 0.4)),
           dict(center=(0, 0, 0), dBunker=0.5, dOutput=0.1, hBunker=0, hOutput=0.15, hPipe=0.05, wallMask=6,
                angleRange=(0.1, 3.0))]:
    fs = geom.facetBunker(**kw)
    print('K %d' % len(fs))
    for b in fs:
        print('K %r %r %r %d' % (list(b.state.pos), list(b.state.ori), [list(v) for v in b.shape.vertices], b.mask))
fs = geom.facetCone((0, 0, 1), 0.3, 0.1, 0.4, segmentsNumber=5)
print('K %d' % len(fs))
for b in fs:
    print('K %r %r' % (list(b.state.pos), [list(v) for v in b.shape.vertices]))
