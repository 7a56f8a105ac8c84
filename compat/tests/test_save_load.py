"""O.save / O.load: ryade's own file format; a file saved earlier in the run loads back to the exact state
(YADE's continuation after its own O.load is the same, bit for bit); YADE's files are refused clearly."""
import os
import subprocess
import sys

from _scripts import COMPAT, needs_compat, needs_yade, tagged_lines, tagged_lines_both


@needs_compat
def test_save_then_load_continues_exactly(tmp_path):
    lines = tagged_lines('ryade', 'save_load.py', args=[str(tmp_path)], tags='ABC')
    a = [ln[2:] for ln in lines if ln[0] == 'A']
    c = [ln[2:] for ln in lines if ln[0] == 'C']
    # 7 bodies after 500 steps, then back to step 300 and again to 500: the same doubles
    assert len(a) == 7 and a == c and a[0].startswith('500 0 ')
    assert 'B 300 7' in lines
    with open(tmp_path / 'scene.xml.bz2', 'rb') as f:
        assert f.read(3) == b'BZh'  # compressed as the name says
    # the loaded state is not the one before the load: the pile moved in those 200 steps
    assert [ln for ln in lines if ln.startswith('A 500 6 ')] != []


@needs_compat
@needs_yade
def test_save_load_as_yade(tmp_path):
    ryade, yade = tagged_lines_both('save_load.py', tmp_path, 'ABC')
    assert ryade == yade


@needs_compat
def test_load_of_foreign_files_is_refused(tmp_path):
    (tmp_path / 'a.xml').write_text('<?xml version="1.0"?><boost_serialization/>')
    script = tmp_path / 's.py'
    script.write_text("O.load('a.xml')\n")
    p = subprocess.run([COMPAT, 'run', str(script)], capture_output=True, text=True, cwd=tmp_path, timeout=300,
                       env=dict(os.environ, RYADE_PYTHON=sys.executable))
    assert p.returncode == 1 and 'ryade does not support O.load of YADE files (.xml/.yade) yet (' in p.stderr
    # a file of ryade's format from another run: the state it names is not in this process
    (tmp_path / 'w.py').write_text("O.bodies.append(utils.sphere((0, 0, 0), 1))\nO.save('b.yade')\n")
    (tmp_path / 'r.py').write_text("O.load('b.yade')\n")
    env = dict(os.environ, RYADE_PYTHON=sys.executable)
    p = subprocess.run([COMPAT, 'run', 'w.py'], capture_output=True, text=True, cwd=tmp_path, timeout=300, env=env)
    assert p.returncode == 0 and (tmp_path / 'b.yade').exists(), p.stderr
    p = subprocess.run([COMPAT, 'run', 'r.py'], capture_output=True, text=True, cwd=tmp_path, timeout=300, env=env)
    assert p.returncode == 1 and 'O.load of a file saved by another run' in p.stderr


@needs_compat
def test_reload_and_filename(tmp_path):
    lines = tagged_lines('ryade', 'reload.py', args=[str(tmp_path)], tags='R')
    assert lines[:4] == ['R None', "R ':memory:'", "R 0 ':memory:'", 'R True']
    assert lines[4].startswith("R 400 'r.xml' [")


@needs_compat
@needs_yade
def test_reload_as_yade(tmp_path):
    ryade, yade = tagged_lines_both('reload.py', tmp_path, 'R')
    assert ryade == yade
