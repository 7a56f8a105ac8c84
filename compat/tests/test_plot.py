"""yade.plot (compat/python/yade/plot.py) against YADE 2023.02a.

The reference files in data/plot/ were written by
``yade -n -x yade_ref/compat/plot/plot_ref.py compat/tests/data/plot``;
these tests run the same functions from that script with ryade's module.
"""
import bz2
import gzip
import importlib.util
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
PYDIR = HERE.parent / 'python'
PLOT_PY = PYDIR / 'yade' / 'plot.py'
REF_DIR = HERE / 'data' / 'plot'
REF_SCRIPT = ROOT / 'yade_ref' / 'compat' / 'plot' / 'plot_ref.py'


def _load_plot():
	"Import yade.plot from compat/python; if the package cannot be imported, load the file alone."
	if str(PYDIR) not in sys.path:
		sys.path.insert(0, str(PYDIR))
	try:
		import yade.plot as mod
		if Path(mod.__file__).resolve() == PLOT_PY.resolve():
			return mod
	except Exception:
		pass
	spec = importlib.util.spec_from_file_location('yade.plot', PLOT_PY)
	mod = importlib.util.module_from_spec(spec)
	sys.modules['yade.plot'] = mod
	spec.loader.exec_module(mod)
	return mod


def _load_ref():
	spec = importlib.util.spec_from_file_location('ryade_plot_ref', REF_SCRIPT)
	mod = importlib.util.module_from_spec(spec)
	spec.loader.exec_module(mod)
	return mod


plot = _load_plot()
ref = _load_ref()


def _has_matplotlib():
	try:
		import matplotlib  # noqa: F401
		return True
	except ImportError:
		return False


needs_mpl = pytest.mark.skipif(not _has_matplotlib(), reason='matplotlib not installed')


# minieigen stand-ins: yade.plot recognises these by type name, components are floats
class Vector2(object):

	def __init__(self, *c):
		self.c = [float(x) for x in c]

	def __getitem__(self, i):
		return self.c[i]

	def __len__(self):
		return len(self.c)


class Vector3(Vector2):
	pass


class Matrix3(object):

	def __init__(self, *c):
		self.c = [float(x) for x in c]

	def __getitem__(self, ij):
		return self.c[3 * ij[0] + ij[1]]

	def __len__(self):
		return 3


@pytest.fixture(autouse=True)
def _clean_state():
	plot.reset()
	plot.imgData.clear()
	plot.labels = {}
	plot.xylabels = {}
	yield
	plot.reset()
	plot.imgData.clear()
	plot._lastSave = None  # no redraw into a test's tmp dir when pytest exits


@pytest.fixture(scope='module')
def seq_dir(tmp_path_factory):
	out = tmp_path_factory.mktemp('plotseq')
	ref.run(plot, Vector2, Vector3, Matrix3, str(out))
	return out


SEQ_FILES = sorted(p.name for p in REF_DIR.iterdir() if p.name not in ('yade_plot.png', 'plot.log.txt'))


def _read(path):
	raw = path.read_bytes()
	if path.name.endswith('.gz'):
		return gzip.decompress(raw)
	if path.name.endswith('.bz2'):
		return bz2.decompress(raw)
	if path.name.endswith('.gnuplot'):
		# line 3 is '# created <asctime> (<YYYYmmdd_HH:MM>)'
		return re.sub(rb'(?m)^# created .*$', b'# created <TIME>', raw)
	return raw


def test_reference_files_present():
	assert 'log.txt' in SEQ_FILES and 'all.txt' in SEQ_FILES and len(SEQ_FILES) == 19


def test_same_file_set(seq_dir):
	assert sorted(p.name for p in seq_dir.iterdir()) == SEQ_FILES


@pytest.mark.parametrize('name', SEQ_FILES)
def test_output_matches_yade(seq_dir, name):
	mine, theirs = _read(seq_dir / name), _read(REF_DIR / name)
	assert mine.decode('utf-8') == theirs.decode('utf-8')


@pytest.mark.parametrize('name', [n for n in SEQ_FILES if n.endswith('.gz')])
def test_gzip_header_matches_yade(seq_dir, name):
	# magic, method, flags, (mtime skipped), xfl, os, original file name
	def header(p):
		raw = p.read_bytes()
		end = raw.index(b'\0', 10)
		return raw[:4] + raw[8:end]

	assert header(seq_dir / name) == header(REF_DIR / name)


def test_final_data_content(seq_dir):
	# data after the fill stage, checked value by value (NaN-aware, with types)
	plot.reset()
	log = ref._Log(str(seq_dir))
	ref._fill(plot, Vector2, Vector3, Matrix3, log)
	text = (REF_DIR / 'log.txt').read_text()
	block = text.split('== data after full sequence')[1].split('\nsaveGnuplot')[0]
	expected = {}
	for line in block.splitlines()[1:]:
		k, v = line.strip().split(': ', 1)
		expected[eval(k)] = eval(v, {'nan': float('nan'), 'inf': float('inf')})
	assert list(plot.data) == list(expected)
	for k, col in expected.items():
		got = plot.data[k]
		assert len(got) == len(col), k
		for a, b in zip(got, col):
			assert type(a) is type(b), (k, a, b)
			assert repr(a) == repr(b), (k, a, b)


def test_addData_examples():
	plot.addData(a=1)
	plot.addData(b=2)
	plot.addData(a=3, b=4)
	assert repr(plot.data) == "{'a': [1, nan, 3], 'b': [nan, 2, 4]}"
	d = {'x': 1.5}
	plot.addData(d, y=2)
	assert d == {'x': 1.5, 'y': 2}  # YADE updates the dict argument in place
	assert repr(plot.data) == "{'a': [1, nan, 3, nan], 'b': [nan, 2, 4, nan], 'x': [nan, nan, nan, 1.5], 'y': [nan, nan, nan, 2]}"
	plot.resetData()
	assert plot.data == {}


def test_timestamp_name(tmp_path):
	plot.addData(i=1, t=2.0)
	plot.plots = {'i': ('t',)}
	name = plot.saveGnuplot(str(tmp_path / 'ts'), timestamp=True)
	assert re.fullmatch(re.escape(str(tmp_path / 'ts')) + r'_\d{8}_\d\d:\d\d\.gnuplot', name)
	assert os.path.exists(name) and os.path.exists(name[:-len('.gnuplot')] + '.data.bz2')


@pytest.mark.parametrize('name', ['savePlotSequence', 'createTitleFrame', 'savePylab', 'liveUpdate'])
def test_unsupported_raise(name):
	fn = getattr(plot, name)
	args = {'savePlotSequence': ('x',), 'createTitleFrame': ('x', (1, 1), 't'), 'savePylab': ('x',), 'liveUpdate': (0,)}[name]
	with pytest.raises(NotImplementedError, match=r'yade\.plot\.%s is not supported by ryade yet' % name):
		fn(*args)


def test_attributes():
	for name in plot.__all__:
		assert hasattr(plot, name), name
	plot.live = True
	plot.liveInterval = .5
	plot.addData(a=1)
	assert plot.data == {'a': [1]}
	plot.live = False
	assert plot.legendLoc == ('upper left', 'upper right')
	assert plot.axesWd == 0 and plot.scientific is True


def test_import_without_matplotlib(tmp_path):
	code = (
	        "import sys, importlib.util\n"
	        "sys.modules['matplotlib'] = None\n"
	        "spec = importlib.util.spec_from_file_location('yade.plot', %r)\n"
	        "m = importlib.util.module_from_spec(spec); sys.modules['yade.plot'] = m; spec.loader.exec_module(m)\n"
	        "m.addData(a=1, b=2.5); m.saveDataTxt(%r)\n"
	        "m.plots = {'a': ('b',)}\n"
	        "try:\n    m.plot()\nexcept ImportError as e:\n    print('ERR', e)\n"
	) % (str(PLOT_PY), str(tmp_path / 'd.txt'))
	r = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True, cwd=str(tmp_path))
	assert r.returncode == 0, r.stderr
	assert 'pip install matplotlib' in r.stdout
	assert (tmp_path / 'd.txt').read_text() == '# a\t\tb\n1\t2.5\n'


@needs_mpl
def test_plot_sequence_matches_yade(tmp_path):
	ref.runPlot(plot, str(tmp_path))
	assert (tmp_path / 'plot.log.txt').read_text() == (REF_DIR / 'plot.log.txt').read_text()


def _fill_for_png():
	plot.labels = {'Ek': 'E_k [J]', 'i': 'iteration', 't': '$t$'}
	for k in range(60):
		plot.addData(i=k, t=k * 1e-3, Ek=(k - 20)**2 * 1e-4, F=(30 - k) * 0.5 if k % 7 else float('nan'), sigma=-k * 1e3)
	plot.plots = {'i': ('t', 'Ek', None, ('F', 'r--')), 't=O.time': ('sigma',)}


def _is_png(p):
	return p.exists() and p.stat().st_size > 1000 and p.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n'


@needs_mpl
def test_plot_headless_png_env(tmp_path, monkeypatch, capsys):
	out = tmp_path / 'sub' / 'fig.png'
	monkeypatch.setenv('RYADE_PLOT_FILE', str(out))
	_fill_for_png()
	assert plot.plot() is None
	assert _is_png(out)
	assert str(out) in capsys.readouterr().out


@needs_mpl
def test_plot_headless_png_default_name(tmp_path, monkeypatch, capsys):
	monkeypatch.delenv('RYADE_PLOT_FILE', raising=False)
	monkeypatch.chdir(tmp_path)
	monkeypatch.setattr(sys, 'argv', [str(tmp_path / 'elsewhere' / 'myscript.py')])
	_fill_for_png()
	plot.plot()
	assert _is_png(tmp_path / 'myscript.plot.png')
	# one file per figure without subplots
	plot.plot(subPlots=False)
	assert _is_png(tmp_path / 'myscript.plot.png') and _is_png(tmp_path / 'myscript.plot.1.png')
	assert 'myscript.plot.1.png' in capsys.readouterr().out


@needs_mpl
def test_plot_redrawn_at_exit(tmp_path):
	# plot() before the data exist (YADE would update its window live): the PNG is redrawn at exit
	script = tmp_path / 'late.py'
	script.write_text(
	        "import sys, importlib.util\n"
	        "spec = importlib.util.spec_from_file_location('yade.plot', %r)\n"
	        "plot = importlib.util.module_from_spec(spec); sys.modules['yade.plot'] = plot; spec.loader.exec_module(plot)\n"
	        "plot.plots = {'i': ('a',)}\n"
	        "plot.plot()\n"
	        "import os; print('SIZE', os.path.getsize('late.plot.png'))\n"
	        "for k in range(50): plot.addData(i=k, a=k * k)\n" % str(PLOT_PY)
	)
	env = dict(os.environ)
	env.pop('RYADE_PLOT_FILE', None)
	env.pop('DISPLAY', None)
	r = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, cwd=str(tmp_path), env=env)
	assert r.returncode == 0, r.stderr
	png = tmp_path / 'late.plot.png'
	assert r.stdout.count(str(png)) == 2, r.stdout
	first = int(re.search(r'SIZE (\d+)', r.stdout).group(1))
	assert _is_png(png) and png.stat().st_size != first


@needs_mpl
def test_plot_noShow_returns_figures(tmp_path):
	import matplotlib.figure
	_fill_for_png()
	plot.axesWd = 1
	plot.xylabels = {'i': ('x axis', None, 'right axis')}
	try:
		fig = plot.plot(noShow=True)
	finally:
		plot.axesWd = 0
	assert isinstance(fig, matplotlib.figure.Figure)
	assert len(fig.axes) == 3  # two subplots + the right axis of the first
	left, right, second = fig.axes
	assert left.get_xlabel() == 'x axis' and left.get_ylabel() == '$t$, E_k [J]'
	assert right.get_ylabel() == 'right axis' and second.get_ylabel() == 'sigma'
	assert [l.get_label() for l in right.get_lines()][0] == 'F'
	fig.savefig(str(tmp_path / 'f.png'))
	assert _is_png(tmp_path / 'f.png')
	figs = plot.plot(noShow=True, subPlots=False)
	assert isinstance(figs, list) and len(figs) == 2


@needs_mpl
def test_plot_callable_dict_and_image_specs(tmp_path):
	import matplotlib.pyplot as plt
	img = tmp_path / 'img.png'
	plt.imsave(str(img), [[0, 1], [1, 0]])
	plot.addData(i=1, a=2, b=3)
	plot.addData(i=2, a=1, b=4)
	plot.addImgData(snap=str(img))
	plot.plots = {'i': (lambda: ['a'], None, {'b': 0}), 'snap': None}
	fig = plot.plot(noShow=True)
	labels = [l.get_label() for ax in fig.axes for l in ax.get_lines() if not l.get_label().startswith('_')]
	assert labels == ['a', 'b']
	fig.savefig(str(tmp_path / 'f.png'))
	assert _is_png(tmp_path / 'f.png')


def test_plot_empty_plots_raises():
	if not _has_matplotlib():
		pytest.skip('matplotlib not installed')
	with pytest.raises(IndexError, match='plot.plots is empty'):
		plot.plot(noShow=True)
