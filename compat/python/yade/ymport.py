"""`yade.ymport` over ryade: sphere lists from text files (as YADE's py/ymport.py reads them)."""

from . import utils
from ._errors import unsupported
from .minieigen import Vector3

__all__ = ['text', 'textExt']


def textExt(fileName, format='x_y_z_r', shift=Vector3(0, 0, 0), scale=1.0, attrs=[], **kw):
    """Spheres from `fileName`; `#format NAME` lines switch the format, other `#` lines are skipped."""
    ret = []
    with open(fileName) as f:
        lines = f.readlines()
    for line in lines:
        data = line.split()
        if not data:
            continue
        if data[0] == "#format":
            format = data[1]
            continue
        elif data[0][0] == "#":
            continue
        if format == 'x_y_z_r':
            pos = Vector3(float(data[0]), float(data[1]), float(data[2]))
            ret.append(utils.sphere(shift + scale * pos, scale * float(data[3]), **kw))
        elif format == 'x_y_z_r_matId':
            pos = Vector3(float(data[0]), float(data[1]), float(data[2]))
            ret.append(utils.sphere(shift + scale * pos, scale * float(data[3]), material=int(data[4]), **kw))
        elif format == 'id_x_y_z_r_matId':
            pos = Vector3(float(data[1]), float(data[2]), float(data[3]))
            ret.append(utils.sphere(shift + scale * pos, scale * float(data[4]), material=int(data[5]), **kw))
        elif format == 'x_y_z_r_attrs':
            pos = Vector3(float(data[0]), float(data[1]), float(data[2]))
            ret.append(utils.sphere(shift + scale * pos, scale * float(data[3]), **kw))
            attrs.append(data[4:])
        else:
            raise RuntimeError("Please, specify a correct format output!")
    return ret


def text(fileName, shift=Vector3(0, 0, 0), scale=1.0, **kw):
    return textExt(fileName=fileName, format='x_y_z_r', shift=shift, scale=scale, **kw)


def __getattr__(name):
    if name.startswith('__'):
        raise AttributeError(name)
    unsupported('yade.ymport.%s' % name)
