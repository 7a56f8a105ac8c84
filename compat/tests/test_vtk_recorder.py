"""VTKRecorder writes YADE's frames and arrays (issue 18): the iteration-0 frame (YADE's initRun) and,
for 'velocity', linVelLen/angVelLen next to the vectors, with YADE's values; 'colors' (issue 19,
funnel.py) the shapes' colours, per sphere and per facet."""
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

from _scripts import COMPAT, SCRIPTS, needs_compat, needs_yade


def arrays(path):
    """Name -> list of floats of every DataArray of a .vtu file (YADE's or ryade's layout)."""
    out = {}
    for a in ET.parse(path).getroot().iter('DataArray'):
        vals = [float(x) for x in (a.text or '').split()]
        out[a.get('Name') or 'Points'] = vals
    return out


def run(engine, out):
    os.makedirs(out, exist_ok=True)
    script = os.path.join(SCRIPTS, 'vtk_recorder.py')
    cmd = [COMPAT, 'run', script, str(out)] if engine == 'ryade' else ['yade', '-n', '-x', script, str(out)]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=300,
                       env=dict(os.environ, RYADE_PYTHON=sys.executable, OMP_NUM_THREADS='1'))
    assert p.returncode == 0, p.stderr


@needs_compat
def test_iteration_zero_frame_and_velocity_lengths(tmp_path):
    run('ryade', tmp_path)
    assert sorted(os.listdir(tmp_path)) == ['r-facets.0.vtu', 'r-facets.100.vtu', 'r-facets.50.vtu',
                                            'r-spheres.0.vtu', 'r-spheres.100.vtu', 'r-spheres.50.vtu']
    a = arrays(tmp_path / 'r-spheres.50.vtu')
    assert [k for k in a if k.endswith('Len')] == ['linVelLen', 'angVelLen']
    for vec, ln in (('linVelVec', 'linVelLen'), ('angVelVec', 'angVelLen')):
        v = a[vec]
        assert a[ln] == [(v[3 * i] ** 2 + (v[3 * i + 1] ** 2 + v[3 * i + 2] ** 2)) ** 0.5 for i in range(len(v) // 3)]


@needs_compat
@needs_yade
def test_arrays_equal_yades(tmp_path):
    run('ryade', tmp_path / 'r')
    run('yade', tmp_path / 'y')
    assert sorted(os.listdir(tmp_path / 'r')) == sorted(os.listdir(tmp_path / 'y'))
    for f in os.listdir(tmp_path / 'y'):
        if 'spheres' in f:
            y, r = arrays(tmp_path / 'y' / f), arrays(tmp_path / 'r' / f)
            for k in ('radii', 'linVelVec', 'angVelVec', 'linVelLen', 'angVelLen', 'color'):
                assert r[k] == y[k], (f, k)
        else:
            y, r = arrays(tmp_path / 'y' / f), arrays(tmp_path / 'r' / f)
            assert r['color'] == y['color'] == [0.7, 0.6, 0.5], f
