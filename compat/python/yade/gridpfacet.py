"""`yade.gridpfacet` over ryade: grid nodes and connections built as YADE's py/gridpfacet.py builds
them (masses, inertias and the Euler-Bernoulli bond stiffnesses are computed by the Rust core's
`utils::grid_connection`, which mirrors that file step by step)."""

from . import utils
from ._core import GridConnection, GridNode, Omega
from ._errors import unsupported
from .minieigen import Vector3i

__all__ = ['gridNode', 'gridConnection', 'cylinder', 'cylinderConnection']


def gridNode(center, radius, dynamic=None, fixed=False, wire=False, color=None, highlight=False, material=-1):
    from ._core import Body
    b = Body()
    b.shape = GridNode(radius=radius, color=color if color else utils.randomColor(), wire=wire, highlight=highlight)
    utils._commonBodySetup(b, 0, (0, 0, 0), material, pos=center, dynamic=dynamic, fixed=fixed)
    b.aspherical = False
    b.bounded = False
    b.mask = 0
    return b


def gridConnection(id1, id2, radius, wire=False, color=None, highlight=False, material=-1, mask=1, cellDist=None):
    O = Omega()
    mat = utils._material(material)
    if mat._owner is None:
        unsupported('gridConnection with a material that is not in O.materials')
    cd = None if cellDist is None else [int(cellDist[0]), int(cellDist[1]), int(cellDist[2])]
    cid = O._sim.grid_connection(int(id1), int(id2), float(radius), mat._owner[1], int(mask), cd)
    shape = GridConnection(radius=radius, color=color if color else utils.randomColor(), wire=wire, highlight=highlight,
                           node1=O.bodies[id1], node2=O.bodies[id2], periodic=O.periodic,
                           cellDist=Vector3i(*(cd or (0, 0, 0))) if O.periodic else Vector3i(0, 0, 0))
    b = O.bodies._adopt(cid, shape, mat)
    object.__setattr__(b, '_pending_append', True)   # YADE returns the Body for the script to append
    return b


def cylinder(begin=(0, 0, 0), end=(1., 0., 0.), radius=0.2, nodesIds=[], cylIds=[], dynamic=None, fixed=False,
             wire=False, color=None, highlight=False, intMaterial=-1, extMaterial=-1, mask=1):
    """A rounded cylinder: two grid nodes (material `intMaterial`) and their connection (`extMaterial`), all
    appended to O.bodies; their ids are appended to `nodesIds` and `cylIds` (YADE's shared default lists
    included)."""
    cylinderConnection([begin, end], radius, nodesIds, cylIds, dynamic, fixed, wire, color, highlight, intMaterial,
                       extMaterial, mask)


def cylinderConnection(vertices, radius=0.2, nodesIds=[], cylIds=[], dynamic=None, fixed=False, wire=False, color=None,
                       highlight=False, intMaterial=-1, extMaterial=-1, mask=1):
    """A chain of rounded cylinders through `vertices`: every node first, then the connections in order."""
    O = Omega()
    nodes = [O.bodies.append(gridNode(v, radius=radius, dynamic=dynamic, fixed=fixed, wire=wire, color=color,
                                      highlight=highlight, material=intMaterial)) for v in vertices]
    nodesIds.extend(nodes)
    for a, b in zip(nodes[:-1], nodes[1:]):
        cylIds.append(O.bodies.append(gridConnection(a, b, radius=radius, wire=wire, color=color, highlight=highlight,
                                                     material=extMaterial, mask=mask, cellDist=None)))


def __getattr__(name):
    if name.startswith('__'):
        raise AttributeError(name)
    unsupported('yade.gridpfacet.%s' % name)
