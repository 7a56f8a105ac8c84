"""RyadePistonController (a ryade extension, src/piston.rs): the study's PI piston law as a Rust engine.

* the study (yade_ref/study/study.py) with `--controller native` writes the same bytes as with
  `--controller pi` (the PyRunner law), on the tiny golden G specimen;
* the engine's stops (approach contact, rut limit) end `O.run` after the step both when the run stays
  in Rust and when a PyRunner makes it loop in Python;
* its boxPorosity is the script's porosity to the bit;
* the Python class: attributes, errors, and that YADE has no such class.
"""
import os
import subprocess
import sys

import pytest

from _scripts import COMPAT, ROOT, SCRIPTS, needs_compat, needs_yade

STUDY = os.path.join(ROOT, 'yade_ref', 'study', 'study.py')
SPECIMEN_G = os.path.join(ROOT, 'golden', 'study', 'r05_G_tiny_s1', 'specimen.json')


def compat_run(*args):
    p = subprocess.run([COMPAT, 'run'] + list(args), capture_output=True, text=True, timeout=600, cwd=ROOT,
                       env=dict(os.environ, RYADE_PYTHON=sys.executable, OMP_NUM_THREADS='1'))
    assert p.returncode == 0, p.stdout + p.stderr
    return p.stdout


@needs_compat
def test_native_controller_writes_the_pi_bytes(tmp_path):
    """G tiny golden specimen, 2 cycles: history.csv, steps.csv and profile.csv byte-identical between
    the PyRunner law and the engine."""
    logs = {}
    for c in ('pi', 'native'):
        logs[c] = compat_run(STUDY, '--import-specimen', SPECIMEN_G, '--cycles', '2', '--controller', c,
                             '--out', str(tmp_path / c))
    assert 'RyadePistonController (ryade engine) runs the law' in logs['native']
    assert 'RyadePistonController' not in logs['pi']
    for f in ('history.csv', 'steps.csv', 'profile.csv'):
        a, b = (tmp_path / 'pi' / f).read_bytes(), (tmp_path / 'native' / f).read_bytes()
        assert a == b, f
    # and it is YADE's history (golden/study, recorded by YADE 2023.02a with the PyRunner law)
    golden = open(os.path.join(ROOT, 'golden', 'study', 'r05_G_tiny_s1', 'history.csv'), 'rb').read()
    assert golden.startswith((tmp_path / 'native' / 'history.csv').read_bytes())


@needs_compat
def test_native_controller_runs_the_subgrade_with_the_pi_bytes(tmp_path):
    """--subgrade-k (the spring bed under the bottom plate, study.py tick_subgrade): the engine steps it
    too, so no PyRunner is left; history.csv (with its subgrade_mm column), steps.csv and profile.csv
    are byte-identical to the PyRunner law's on the YADE-order path, and the fast path takes the run."""
    logs = {}
    for c in ('pi', 'native'):
        logs[c] = compat_run(STUDY, '--import-specimen', SPECIMEN_G, '--cycles', '2', '--controller', c,
                             '--subgrade-k', '1e7', '--out', str(tmp_path / c))
    assert 'RyadePistonController (ryade engine) runs the law' in logs['native']
    for f in ('history.csv', 'steps.csv', 'profile.csv'):
        a, b = (tmp_path / 'pi' / f).read_bytes(), (tmp_path / 'native' / f).read_bytes()
        assert a == b, f
    head = (tmp_path / 'native' / 'history.csv').read_text().splitlines()
    assert head[0].endswith(',subgrade_mm')
    # the plate moved: its settlement under the layer's weight and the load
    assert float(head[-1].split(',')[-1]) != 0.0
    fast = compat_run('--fast', STUDY, '--import-specimen', SPECIMEN_G, '--cycles', '2', '--controller', 'native',
                      '--subgrade-k', '1e7', '--out', str(tmp_path / 'fast'))
    assert 'YADE-order path for this run' not in fast, fast
    rows = (tmp_path / 'fast' / 'history.csv').read_text().splitlines()
    assert len(rows) == len(head) and rows[0] == head[0]


@needs_compat
def test_box_porosity_is_the_scripts_to_the_bit():
    """boxPorosity (the study's porosity in the Rust core, used by study.py under --controller native)
    equals the script's own Python box_porosity exactly, on 600 random spheres in a periodic cell
    whose faces, edges, corners and periodic images cut four boxes, and sphere by sphere in boxes of
    about its size (where one ulp of a volume shows); a bad id is a clear error."""
    out = compat_run(os.path.join(SCRIPTS, 'porosity_native.py'), STUDY).splitlines()
    rows = [ln.split()[1:] for ln in out if ln.startswith('B ')]
    assert len(rows) == 4
    for py, native in rows:
        assert py == native
        assert 0.5 < float(py) < 1.0
    single = [ln.split()[1:] for ln in out if ln.startswith('S ')]
    assert len(single) == 300 and all(py == native for py, native in single)
    assert sum(1 for py, _ in single if 0.05 < float(py) < 0.95) > 100  # spheres that the box cuts
    assert any(ln.startswith('E ') and 'body 1000000 is not a sphere' in ln for ln in out)


@needs_compat
def test_stops_end_the_run_in_rust_and_in_the_python_loop():
    out = compat_run(os.path.join(SCRIPTS, 'piston_native.py')).splitlines()
    rust = [ln[2:] for ln in out if ln.startswith('R ')]
    py = [ln[2:] for ln in out if ln.startswith('P ')]
    assert len(rust) == 3 and rust == py
    approach = rust[0].split()
    # stopped at the contact (p >= pSeat = 2000 Pa), not at the cap of 100000 steps
    assert approach[1] != '100000' and approach[2] == 'idle' and float(approach[3]) >= 2000.0
    cycle = rust[1].split()
    assert cycle[2] == '1000' and cycle[-1] == 'False'  # one statistic per step, no stop
    stop = rust[2].split()
    assert int(stop[1]) < int(cycle[1]) + 1000 and stop[3:5] == ['True', 'idle']  # the rut stop


@needs_compat
def test_python_class_attributes_and_errors():
    from yade import wrapper
    assert 'RyadePistonController' in wrapper.RYADE_EXTENSIONS
    assert 'RyadePistonController' not in wrapper.YADE_CLASSES
    pc = wrapper.RyadePistonController(ids=[3, 4], Kp=1, wave='triangle')
    assert pc.Kp == 1.0 and isinstance(pc.Kp, float) and pc.iterPeriod == 1 and pc.phase == 'idle'
    assert pc.stopRut == float('inf') and pc.peak == -1e300 and pc.takeSteps() == []
    with pytest.raises(ValueError, match='wave'):
        pc.wave = 'square'
    with pytest.raises(ValueError, match='negative body id'):
        pc.ids = [-1]
    with pytest.raises(AttributeError):
        pc.kp = 1.0


@needs_yade
def test_yade_has_no_such_class(tmp_path):
    s = tmp_path / 's.py'
    s.write_text('RyadePistonController()\n')
    p = subprocess.run(['yade', '-n', '-x', str(s)], capture_output=True, text=True, timeout=300,
                       env=dict(os.environ, OMP_NUM_THREADS='1'))
    assert "name 'RyadePistonController' is not defined" in p.stdout + p.stderr
