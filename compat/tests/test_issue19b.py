"""What issue 19's second session added to the compat layer and the core, against the lines Debian's YADE
2023.02a printed for data/scripts/issue19b_features.py (`yade -n -x`; run live too when YADE is
installed): the `+` of kinematic engines (CombinedKinematicEngine), SpherePack.psd, yade.math and
`opts`, attributes of a script's own on YADE objects, dispMatrix, a TriaxialStressController run with
internal compaction and its TriaxialStateRecorder file, a Hertz-Mindlin contact with a functor attribute
set after O.engines was assigned."""
import pytest

from _scripts import needs_compat, needs_yade, tagged_lines_both, tagged_lines

YADE_LINES = [
    "A CombinedKinematicEngine True 3 [3, 4] ['TranslationEngine', 'RotationEngine', 'HelixEngine']",
    'B 322 0.09269172910589876 0.32717749907162585 0.4596273291925472 8 8',
    'C 0.1 0.3490658503988659 28.64788975654116 True',
    "D kept [(('Facet', 'Sphere'), 'Ig2_Facet_Sphere_ScGeom'), (('Sphere', 'Facet'), 'Ig2_Facet_Sphere_ScGeom'), (('Sphere', 'Sphere'), 'Ig2_Sphere_Sphere_ScGeom')] {('ScGeom', 'FrictPhys'): 'Law2_ScGeom_FrictPhys_CundallStrack'}",
    'E -179.03072090055193 0.6158973817880067 -0.0 0.0 0.015947092890712295 1.002',
    'R iteration s11 s22 s33 e11 e22 e33 unb_force porosity kineticE',
    'R 0 -0 -0 -0 0 0 0 -nan 0.94598322256141221 0',
    'R 150 -0 -0 -0 0 0 0 0.049999999999999996 0.87009812721836921 0.024434303434903232',
    'R 300 -0 -0 -0 0 0 0 0.19271142741769912 0.74558889520477822 0.095381241847720649',
    'R 450 -79.281676995747034 -0 -0 0 0 0 0.25998118493397265 0.64028450584529328 0.059374608072488205',
    'F MindlinPhys 404047.07840499753 21.24746289306302 -0.5586709137207582 0.2 31081616.75545264 -0.04019362109715268',
]


@needs_compat
def test_issue19b_features_equal_yade(tmp_path):
    assert tagged_lines('ryade', 'issue19b_features.py', [str(tmp_path)]) == YADE_LINES


@needs_compat
@needs_yade
def test_issue19b_features_live_yade(tmp_path):
    ryade, yade = tagged_lines_both('issue19b_features.py', tmp_path, 'ABCDEFR')
    assert ryade == yade


@needs_compat
def test_domain_limiter_refuses_to_erase(tmp_path):
    """DomainLimiter runs YADE's domain check; a body it would delete stops the run with the
    does-not-support error (ryade cannot erase bodies yet)."""
    import subprocess, sys, os
    from _scripts import COMPAT
    script = tmp_path / 'dl.py'
    script.write_text("O.bodies.append(sphere((0, 0, 5), 1))\n"
                      "O.engines = [ForceResetter(), DomainLimiter(lo=(-1, -1, -1), hi=(1, 1, 1), iterPeriod=1), "
                      "NewtonIntegrator()]\nO.dt = 1e-3\nO.run(3, True)\n")
    p = subprocess.run([COMPAT, 'run', str(script)], capture_output=True, text=True, timeout=120,
                       env=dict(os.environ, RYADE_PYTHON=sys.executable))
    assert p.returncode != 0
    assert 'does not support DomainLimiter deleting bodies (#0' in p.stderr
