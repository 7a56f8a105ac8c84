"""O.energy (O.trackEnergy) equals YADE's: the golden/energy scenes recorded by YADE 2023.02a every step
(yade_ref/energy/*.py: NewtonIntegrator's nonviscDamp, kinetic, gravWork on spheres, a clump, blocked
DOFs and a moving fixed body over facets; CohesionMoment's shear/bending/twist dissipation; the law's
elastPotential/plastDissip; PeriTriaxController's velGradWork) rerun under `compat run` give the same
bytes. Before the Newton terms existed, O.energy.total() was 5.01 where YADE has 0.98 (issue 18)."""
import os
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
COMPAT = os.environ.get('COMPAT', os.path.join(ROOT, 'target', 'release', 'compat'))
GOLD = os.path.join(ROOT, 'golden', 'energy')

pytestmark = pytest.mark.skipif(not os.path.exists(COMPAT), reason='build the compat binary first (cargo build --release)')


@pytest.mark.parametrize('scene', ['facet', 'coh', 'peri'])
def test_energy_equals_yade_every_step(scene, tmp_path):
    script = os.path.join(ROOT, 'yade_ref', 'energy', 'energy_%s.py' % scene)
    p = subprocess.run([COMPAT, 'run', script, str(tmp_path)], capture_output=True, text=True, timeout=600,
                       env=dict(os.environ, RYADE_PYTHON=sys.executable))
    assert p.returncode == 0, p.stderr
    name = 'energy_%s.csv' % scene
    got = open(tmp_path / name).read().splitlines()
    want = open(os.path.join(GOLD, name)).read().splitlines()
    assert len(got) == len(want)
    for k, (g, w) in enumerate(zip(got, want)):
        assert g == w, 'row %d differs from YADE:\n ryade %s\n YADE  %s' % (k + 1, g[:300], w[:300])


def test_energy_api_as_yade():
    """KeyError text, items() in name order, total() in creation order, __setitem__, clear() (whose
    odd YADE semantics are covered by src/energy.rs's tests against a YADE run)."""
    code = r'''
O.trackEnergy = True
O.energy['b'] = 1.0
O.energy['a'] = 2.0
print(O.energy.items(), O.energy.keys(), O.energy.total())
try:
    O.energy['zz']
except KeyError as e:
    print('KeyError', e)
O.energy.clear()
print(O.energy.items(), O.energy.total())
'''
    p = subprocess.run([sys.executable, '-c', 'from yade import *\n' + code], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert p.stdout.splitlines() == ["[('a', 2.0), ('b', 1.0)] ['a', 'b'] 3.0",
                                     "KeyError \"Unknown energy name 'zz'.\"",
                                     "[] 0.0"]


# printed by `yade -n -x data/scripts/kinetic_clump.py` (YADE 2023.02a): the clump counts once (not its
# members) and its rotation as 0.5 w.(T I T^T) w
KINETIC_CLUMP_YADE = ['K 150 1.0615659510297015', 'K 300 4.2462638041188105', 'K 450 9.554093559267328',
                      'K 600 7.884438663097596', 'K 750 4.270058363548972', 'K 900 3.75094939298148']


def test_kinetic_energy_of_a_clump_as_yade():
    from _scripts import tagged_lines
    assert tagged_lines('ryade', 'kinetic_clump.py', tags='K') == KINETIC_CLUMP_YADE


def test_newton_prev_vel_grad_is_the_integrators():
    """Audit (issue 18): NewtonIntegrator.prevVelGrad used to be a constant zero; YADE 2023.02a prints the
    cell's velGrad of the last step (the second line)."""
    code = r'''
O.periodic = True
O.cell.setBox(1, 1, 1)
O.bodies.append(sphere((0.5, 0.5, 0.5), 0.1))
newton = NewtonIntegrator()
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]), newton]
O.dt = 1e-4
print(newton.prevVelGrad)
O.cell.velGrad = Matrix3(0.1, 0, 0, 0, -0.2, 0, 0, 0, 0.3)
O.run(3, True)
print(newton.prevVelGrad)
'''
    p = subprocess.run([sys.executable, '-c', 'from yade import *\nfrom yade.utils import *\n' + code], capture_output=True,
                       text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert p.stdout.splitlines() == ['Matrix3(0,0,0, 0,0,0, 0,0,0)',
                                     'Matrix3(0.1000000000000000056,0,0, 0,-0.2000000000000000111,0, 0,0,0.2999999999999999889)']
