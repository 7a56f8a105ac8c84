# encoding: utf-8
"""Reference run of ``yade.plot`` data handling and text export.

    yade -n -x yade_ref/compat/plot/plot_ref.py OUTDIR

writes into OUTDIR the files that ``compat/tests/test_plot.py`` compares
ryade's ``yade.plot`` against (the committed copy is ``compat/tests/data/plot/``):

* ``log.txt``: ``repr`` of ``plot.data`` (column order, values, int/float/bool
  types, NaN padding) after each stage, messages printed by the module,
  exceptions (type and message) and return values;
* ``*.txt``, ``*.txt.gz``, ``*.txt.bz2``: ``plot.saveDataTxt`` outputs;
* ``gp_*.gnuplot`` and ``gp_*.data.bz2``: ``plot.saveGnuplot`` outputs (line 3
  of a .gnuplot file carries the creation time, gzip headers carry mtime);
* ``plot.log.txt``: what ``plot.plot(noShow=True)`` prints and does to the data;
* ``yade_plot.png``: YADE's own rendering of the gnuplot ``plots`` (for eyes only).

The test imports this file and calls :func:`run` with ryade's module and
stand-in Vector2/Vector3/Matrix3 classes, so both sides run the same sequence.
"""
import contextlib
import glob
import io
import os
import re
import sys


class _Log(object):

	def __init__(self, outdir):
		self.outdir = outdir
		self.lines = []

	def __call__(self, *items):
		self.lines.append(' '.join(str(i) for i in items))

	def data(self, plot, stage, sort=False):
		self('== data after', stage, '(%d columns%s)' % (len(plot.data), ', sorted' if sort else ''))
		for k in (sorted(plot.data) if sort else plot.data):
			self('  %r: %r' % (k, plot.data[k]))

	def path(self, p):
		return str(p).replace(self.outdir, '<OUT>')

	def save(self, name):
		with open(os.path.join(self.outdir, name), 'w') as f:
			f.write('\n'.join(self.lines) + '\n')


@contextlib.contextmanager
def _captured(log, what):
	buf = io.StringIO()
	try:
		with contextlib.redirect_stdout(buf):
			yield
	except Exception as e:
		log('!!', what, 'raised', type(e).__name__ + ':', str(e))
	finally:
		for line in buf.getvalue().splitlines():
			log('>>', what, 'printed:', line)


def _fill(plot, Vector2, Vector3, Matrix3, log):
	plot.reset()
	plot.resetData()
	plot.imgData.clear()
	plot.labels = {}
	plot.xylabels = {}
	plot.addData(i=0, t=0.0, Ek=1.5)
	plot.addData(i=1, t=1e-5, Ek=-2.25e-7, F=3)  # F appears late
	plot.addData(i=2, t=2e-5, F=-4.5)  # Ek missing
	log.data(plot, 'late/missing columns')
	d = {'i': 3, 't': 3.0000000000000004e-05}
	plot.addData(d, sigma=-1.2345678901234567e-300)  # dict + keywords
	log('dict argument afterwards:', sorted(d.items()))
	d = {'i': 4}
	plot.addData(d, w=Vector3(1, -2, 0.5))
	log('dict argument afterwards:', sorted(d.keys()))
	plot.addData(i=5, M=Matrix3(1, 2, 3, 4, 5, 6, 7, 8, 9.5), v2=Vector2(0.1, -0.2))
	log.data(plot, 'vector/matrix columns')
	plot.splitData()
	plot.addData(i=6, t=1e16, Ek=float('inf'), F=-0.0, flag=True, big=12345678901234567890)
	plot.addData(i=7, t=0.1 + 0.2, Ek=1 / 3., F=-1e-320, sigma=123456789.125, tiny=5e-324)
	with _captured(log, 'addData(bad=[1,2])'):
		plot.addData(bad=[1, 2])
	with _captured(log, "addData(s='text')"):
		plot.addData(i=99, s='text')
	with _captured(log, 'addData(v=(1,2))'):
		plot.addData(v=(1, 2))
	plot.addDataColumns(['extra', 'i'])
	plot.addData(i=8, extra=-7)
	plot.componentSeparator = '::'
	plot.addData(i=9, q=Vector2(2, 3))
	plot.componentSeparator = '_'
	log.data(plot, 'full sequence')


def _exportData(plot, log, out):
	plot.saveDataTxt(os.path.join(out, 'all.txt'))
	plot.saveDataTxt(os.path.join(out, 'all.txt.gz'))
	plot.saveDataTxt(os.path.join(out, 'all.txt.bz2'))
	plot.saveDataTxt(os.path.join(out, 'sub.txt'), vars=('t', 'i', 'Ek', 'M_xy'))
	plot.saveDataTxt(os.path.join(out, 'hdr.txt.gz'), vars=['i', 'F'], headers={'nSteps': 8, 'title': 'run A', 'dt': 1e-5, 'v': (1, 2)})
	plot.saveDataTxt(os.path.join(out, 'hdr.txt'), vars=['i'], headers={'b': 'x'})
	plot.saveDataTxt(os.path.join(out, 'novars.txt'), vars=[])  # empty: all columns


def _exportGnuplot(plot, log, out):
	plot.labels = {'Ek': 'E_k [J]', 'i': 'iteration', 't': '$t$'}

	def wNames():
		return ['w_x', 'nope', 'w_z']

	class Energy(object):  # dict-like y specification, like O.energy

		def keys(self):
			return ['M_xx', 'zzz', 'M_yy']

		def items(self):
			return [('M_xx', 'b-'), ('zzz', ''), ('M_yy', 'g')]

	plot.plots = {
	        'i': ('t', 'Ek', None, ('F', 'r--'), 'sigma=whatever'),
	        't=O.time': ('sigma',),
	        'i ': (wNames, None, Energy()),
	        'img': None,
	        'F': 'flag',
	}
	gp = lambda name, **kw: log('saveGnuplot', name, kw, '->', log.path(plot.saveGnuplot(os.path.join(out, name), **kw)))
	gp('gp_default')
	gp('gp_png', term='png', comment='first line\nsecond line', title='My title')
	gp('gp_pdf', term='cairopdf', extension='pdf', varData=True)
	gp('gp_x11', term='x11', comment='single')
	ts = plot.saveGnuplot(os.path.join(out, 'gp_ts'), timestamp=True)
	log('saveGnuplot timestamp=True ->', re.sub(r'_\d{8}_\d\d:\d\d', '_<STAMP>', log.path(ts)))
	for f in glob.glob(os.path.join(out, 'gp_ts_*')):
		os.remove(f)
	plot.plots = {'i': ('t', 'ghost')}
	with _captured(log, 'saveGnuplot gp_err (missing y column)'):
		plot.saveGnuplot(os.path.join(out, 'gp_err'))


def _autoData(plot, log):
	plot.resetData()
	plot.plots = {'a=1+1': ('b=2.5*2', 'math.sqrt(2)', 'nonexistent_name', {'k1': 7, 'k2': -0.5}, None, 'c=undefined_c'), ' z = 3 ': None}
	with _captured(log, 'addAutoData #1'):
		plot.addAutoData()
	plot.plots['x=len(data)'] = (('y=-1e-9', 'r'),)
	with _captured(log, 'addAutoData #2'):
		plot.addAutoData()
	log.data(plot, 'addAutoData')


def _misc(plot, log, out):
	plot.resetData()
	plot.data['pre'] = [1, 2]  # column created by hand
	plot.addData(q=5)
	plot.reverseData()
	log.data(plot, 'hand-made column + reverseData')
	plot.data = {'s': [1], 'l': [1, 2, 3]}  # first column shorter than the rest
	plot.addData(s=2)
	log.data(plot, 'uneven columns')
	plot.resetData()
	plot.addData(a=1)
	plot.addImgData(img='f1.png')
	plot.addData(a=2)
	plot.addData(a=3)
	plot.addImgData(img='f3.png', other='o.png')
	plot.addImgData(other='o2.png')
	log.data(plot, 'addImgData')
	log('imgData:', sorted(plot.imgData.items()))
	plot.imgData.clear()
	plot.labels = {'a': 'A'}
	plot.plots = {'a': ('b',)}
	plot.reset()
	log('after reset: labels', plot.labels, 'plots', plot.plots, 'data', plot.data)
	log('setLiveForceAlwaysUpdate(False) ->', plot.setLiveForceAlwaysUpdate(False))
	with _captured(log, 'saveGnuplot with no data'):
		plot.saveGnuplot(os.path.join(out, 'gp_none'))
	plot.resetData()
	with _captured(log, 'saveDataTxt with no data'):
		plot.saveDataTxt(os.path.join(out, 'empty.txt'))


def run(plot, Vector2, Vector3, Matrix3, out):
	"Run the whole sequence with module *plot*, writing into directory *out*."
	log = _Log(out)
	_fill(plot, Vector2, Vector3, Matrix3, log)
	_exportData(plot, log, out)
	_exportGnuplot(plot, log, out)
	_autoData(plot, log)
	_misc(plot, log, out)
	log.save('log.txt')


def runPlot(plot, out, png=None):
	"plot.plot(noShow=True): messages and effect on data; optionally save the main figure to *png*."
	log = _Log(out)  # columns sorted: YADE adds missing ones in set order
	plot.reset()
	plot.resetData()
	plot.labels = {}
	plot.plots = {'i': ('a', 'missing1')}
	plot.addData(i=1, a=2)
	with _captured(log, 'plot #1'):
		fig = plot.plot(noShow=True)
		log('plot #1 returned', type(fig).__name__)
	log.data(plot, 'plot with a missing column', sort=True)
	plot.resetData()
	plot.plots = {'i': ('a', 'b')}
	with _captured(log, 'plot #2 (no data)'):
		plot.plot(noShow=True)
	log.data(plot, 'plot with no data', sort=True)
	plot.plots = {'i': (lambda: [],)}
	plot.addData(i=1)
	with _captured(log, 'plot #3 (no y)'):
		plot.plot(noShow=True)
	plot.plots = {'a': ('b',), 'i': ('a', None, 'b')}  # nothing missing: YADE prints a set
	with _captured(log, 'plot #4 (subPlots=False)'):
		figs = plot.plot(noShow=True, subPlots=False)
		log('plot #4 returned', type(figs).__name__, len(figs))
	log.data(plot, 'plot #3, #4', sort=True)
	log.save('plot.log.txt')
	if png:
		plot.reset()
		plot.resetData()
		plot.labels = {'Ek': 'E_k [J]', 'i': 'iteration', 't': '$t$'}
		for k in range(60):
			plot.addData(i=k, t=k * 1e-3, Ek=(k - 20)**2 * 1e-4, F=(30 - k) * 0.5 if k % 7 else float('nan'), sigma=-k * 1e3)
		plot.plots = {'i': ('t', 'Ek', None, ('F', 'r--')), 't=O.time': ('sigma',)}
		plot.plot(noShow=True).savefig(png)
		plot.reset()


if __name__ == '__main__':
	import yade.plot
	_out = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else '.')
	os.makedirs(_out, exist_ok=True)
	run(yade.plot, Vector2, Vector3, Matrix3, _out)
	runPlot(yade.plot, _out, png=os.path.join(_out, 'yade_plot.png'))
	print('plot_ref: wrote', _out)
