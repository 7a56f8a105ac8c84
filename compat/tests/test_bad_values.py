"""Bad values name themselves (issue 18): a NaN or infinity given to a body builder, a body, a material or
an engine stops the script with the argument or attribute and its value, not with the JSON parser's
`expected value at line 1 column 233`; a non-finite state in a run says what was found."""
import os
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
COMPAT = os.environ.get('COMPAT', os.path.join(ROOT, 'target', 'release', 'compat'))
SCRIPT = os.path.join(HERE, 'data', 'scripts', 'non_finite_args.py')

pytestmark = pytest.mark.skipif(not os.path.exists(COMPAT), reason='build the compat binary first (cargo build --release)')


@pytest.mark.parametrize('case,want', [
    ('sphere', 'utils.sphere: center = (0, 0, nan) is not finite'),
    ('radius', 'utils.sphere: radius = inf is not finite'),
    ('state', 'O.bodies.append: body #0: vel = (0.0, nan, 0.0) is not finite'),
    ('material', 'O.materials.append(FrictMat): young = nan is not finite'),
    ('engine', 'O.engines[1] (NewtonIntegrator): gravity = (0.0, 0.0, nan) is not finite'),
    ('live', 'NewtonIntegrator.gravity = (0.0, inf, 0.0) is not finite'),
])
def test_non_finite_value_names_the_argument(case, want):
    p = subprocess.run([COMPAT, 'run', SCRIPT, case], capture_output=True, text=True, timeout=120,
                       env=dict(os.environ, RYADE_PYTHON=sys.executable))
    assert p.returncode == 1
    assert want in p.stderr, p.stderr
    assert 'non_finite_args.py, line' in p.stderr
    assert 'column' not in p.stderr


def test_non_finite_state_in_a_run_says_what_was_found(tmp_path):
    script = tmp_path / 'nan_run.py'
    script.write_text('''from yade import utils
O.materials.append(FrictMat(young=1e7, density=2600))
O.bodies.append([utils.sphere((0, 0, 0), 0.01, fixed=True), utils.sphere((0, 0, 0.0199), 0.01)])
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(gravity=(0, 0, -9.81))]
O.dt = 0.5 * utils.PWaveTimeStep()
O.run(10, True)
O.bodies[1].state.vel = Vector3(0, 0, 1e308)
O.bodies[1].state.vel = O.bodies[1].state.vel * 10
O.run(10, True)
''')
    p = subprocess.run([COMPAT, 'run', str(script)], capture_output=True, text=True, timeout=120,
                       env=dict(os.environ, RYADE_PYTHON=sys.executable))
    assert p.returncode == 1
    assert 'step 10: body #1 (Sphere of radius 1e-2 m' in p.stderr, p.stderr
    assert '0.500 x the critical time step' in p.stderr
    assert 'above the critical' not in p.stderr
    assert 'already not finite' in p.stderr
