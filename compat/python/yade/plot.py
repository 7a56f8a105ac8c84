# encoding: utf-8
"""Headless re-implementation of YADE's ``yade.plot`` module for ryade.

Data handling (:func:`addData`, :data:`data`, NaN padding, vector/matrix
component columns), the text exporters (:func:`saveDataTxt`,
:func:`saveGnuplot`) and :func:`addAutoData` follow YADE 2023.02a exactly
(the tests in ``compat/tests/test_plot.py`` compare them with files written
by YADE itself).

:func:`plot` draws the :data:`plots` specification with matplotlib.  ryade
runs scripts without a GUI, so no window is ever opened: with
``noShow=False`` the figure is written to a PNG file (``$RYADE_PLOT_FILE``,
else ``<script stem>.plot.png`` in the working directory) and the path is
printed; with ``noShow=True`` the figure (or list of figures) is returned,
as in YADE.  matplotlib is imported only when something needs it, so this
module imports fine without it.
"""

import itertools  # noqa: F401  (YADE's module has it; addAutoData expressions may use it)
import math
import os
import sys
import threading
import time
import warnings

__all__ = [
        'data', 'plots', 'labels', 'live', 'liveInterval', 'setLiveForceAlwaysUpdate', 'autozoom', 'plot', 'reset', 'resetData', 'splitData', 'reverseData',
        'addData', 'addAutoData', 'saveGnuplot', 'saveDataTxt', 'savePlotSequence'
]

nan = float('nan')

data = {}
"Column name -> list of values; all columns always have the same length (missing values are NaN)."
imgData = {}
"Column name -> list of image file names (or None), one per row of :data:`data`."
plots = {}
"x name -> y specification: a name, ``(name, linespec)``, callable, dict-like object, or a tuple of those; ``None`` inside the tuple switches to the right axis; ``None`` instead of the tuple means an image plot."
labels = {}
"Column name -> human-readable label used in plots and gnuplot files."
xylabels = {}
"x name (key of :data:`plots`) -> (xlabel, ylabel[, y2label]); a false item keeps the automatic label."
legendLoc = ('upper left', 'upper right')
"Legend locations for the left and right axes (used only when a right axis exists)."

plotSyncLock = threading.Lock()
"Lock held by :func:`addData` while live updating is forced (see :func:`setLiveForceAlwaysUpdate`)."
liveForceAlwaysUpdate = False
live = False
"Accepted for compatibility; ryade never updates plots live (no GUI)."
liveInterval = 1
"Accepted for compatibility; unused."
autozoom = True
"Accepted for compatibility; unused."
scientific = True
"Use scientific notation for tick labels."
axesWd = 0
"If positive, draw the x=0 and y=0 axes with this line width (points)."
current = -1
"Index of the row marked with the arrow-shaped marker (-1: the last one)."
afterCurrentAlpha = .2
"Alpha of the part of lines after :data:`current`."
scatterMarkerKw = dict(marker=[(0., 0.), (-30., 10.), (-25, 0), (-30., -10.)])
"Keyword arguments for the marker of the current point."

componentSeparator = '_'
# Sequence values given to addData are split into one column per component.
# Keys are type names (ryade's vector types need not be minieigen's classes);
# a key may also be a type object.
componentSuffixes = {
        'Vector2': {0: 'x', 1: 'y'},
        'Vector3': {0: 'x', 1: 'y', 2: 'z'},
        'Matrix3': {
                (0, 0): 'xx',
                (1, 1): 'yy',
                (2, 2): 'zz',
                (0, 1): 'xy',
                (0, 2): 'xz',
                (1, 2): 'yz',
                (1, 0): 'yx',
                (2, 0): 'zx',
                (2, 1): 'zy'
        },
}

currLineRefs = []
liveTimeStamp = 0

_NOT_SUPPORTED = 'yade.plot.%s is not supported by ryade yet'


# ---------------------------------------------------------------- data


def reset():
	"Clear :data:`data` and :data:`plots` and close all figures (like YADE, :data:`labels` and :data:`imgData` are kept)."
	global data, plots, currLineRefs
	data = {}
	plots = {}
	currLineRefs = []
	plt = sys.modules.get('matplotlib.pyplot')
	if plt is not None:
		plt.close('all')


def resetData():
	"Clear :data:`data`; :data:`plots` and :data:`labels` stay."
	global data
	data = {}


def splitData():
	"Append a row of NaNs, which breaks all plotted lines at this point."
	addData({})


def reverseData():
	"Reverse the row order of every column of :data:`data` in place."
	for col in data.values():
		col.reverse()


def _numRows():
	for col in data.values():
		return len(col)
	return 0


def addDataColumns(dd):
	"Create the named columns (filled with NaN) that do not exist yet; existing columns are left alone."
	n = _numRows()
	for name in dd:
		if name not in data:
			data[name] = [nan] * n


def _componentSuffixes(value):
	t = type(value)
	if t in componentSuffixes:
		return componentSuffixes[t]
	return componentSuffixes.get(t.__name__)


def _componentTypeNames():
	return '/'.join(k if isinstance(k, str) else k.__name__ for k in componentSuffixes)


def addData(*d_in, **kw):
	"""Append one row to :data:`data`: ``addData(name=value, ...)`` or ``addData({'name': value, ...}, ...)``.

	Columns not given in this call get NaN; columns that appear for the first
	time are padded with NaN for the earlier rows.  Vector2/Vector3/Matrix3
	values become one column per component (``name_x``, ``name_xy``, ...);
	other sequences are rejected with ValueError.  As in YADE, a dict passed
	positionally is updated in place with the keyword arguments.
	"""
	locked = False
	if live and liveForceAlwaysUpdate:
		plotSyncLock.acquire()
		locked = True
	try:
		n = _numRows()
		if n == 0 and imgData:
			for col in imgData.values():
				n = len(col)
				break
		row = d_in[0] if d_in else {}
		row.update(**kw)
		for name in list(row.keys()):
			value = row[name]
			suffixes = _componentSuffixes(value)
			if suffixes is not None:
				for index, suffix in suffixes.items():
					row[name + componentSeparator + suffix] = value[index]
				del row[name]
			elif hasattr(value, '__len__'):
				raise ValueError(
				        'plot.addData given unhandled sequence type (is a %s, must be number or %s)' % (type(value).__name__, _componentTypeNames())
				)
		for name in row:
			if name not in data:
				data[name] = []
		for name, col in data.items():
			if len(col) < n:
				col.extend([nan] * (n - len(col)))
			col.append(row[name] if name in row else nan)
	finally:
		if locked and plotSyncLock.locked():
			plotSyncLock.release()


def setLiveForceAlwaysUpdate(forceLiveUpdate):
	"Set whether :func:`addData` takes :data:`plotSyncLock`; returns the new value, or a message if the lock is busy."
	global liveForceAlwaysUpdate
	if plotSyncLock.acquire(blocking=False):
		liveForceAlwaysUpdate = forceLiveUpdate
		plotSyncLock.release()
		return forceLiveUpdate
	return "setLiveForceAlwaysUpdate(" + str(forceLiveUpdate) + "); failed. Try again after pausing the simulation with :yref:`O.pause()<Omega.pause>`."


def addImgData(**kw):
	"Append image file names (one per keyword) to :data:`imgData`, keeping it aligned with :data:`data`."
	for k in kw:
		imgData.setdefault(k, [])
	if data and imgData:
		nData = _numRows()
		nImg = len(next(iter(imgData.values())))
		if nImg < nData - 1:
			# images lag behind data: repeat each column's last image
			for k, col in imgData.items():
				last = col[-1] if col else None
				col.extend([last] * (nData - len(col) - 1))
		elif nData < nImg:
			# data lag behind images: repeat each data column's last value
			for k, col in data.items():
				last = col[-1] if col else nan
				col.extend([last] * (nImg - nData))
	newLen = (len(next(iter(imgData.values()))) if imgData else 0) + 1
	for k, v in kw.items():
		col = imgData.get(k)
		if col:
			col.extend([col[-1]] * (newLen - len(col) - 1))
			col.append(v)
		else:
			imgData[k] = [None] * (newLen - 1) + [v]
	for k, col in imgData.items():
		if len(col) < newLen:
			col.extend([col[-1]] * (newLen - len(col)))
	assert len(set(len(c) for c in imgData.values())) <= 1


# ---------------------------------------------------------------- plot specification helpers


def addPointTypeSpecifier(o, noSplit=False):
	"Turn a y specification into a ``(name, linespec)`` tuple; unless *noSplit*, a ``name=expr`` string is cut to ``name``."
	if type(o) in (tuple, list):
		if noSplit or type(o[0]) is not str:
			return o
		return (o[0].split('=', 1)[0],) + tuple(o[1:])
	if noSplit or type(o) is not str:
		return (o, '')
	return (o.split('=', 1)[0], '')


def tuplifyYAxis(pp):
	"Wrap a single y specification in a 1-tuple; tuples and lists are returned as they are."
	if type(pp) in (tuple, list):
		return pp
	return (pp,)


def xlateLabel(l):
	"The label for column *l* from :data:`labels`, or *l* itself."
	if l in labels:
		return labels[l]
	return l


def _evalNamespace():
	ns = {}
	for modName in ('yade', 'yade.wrapper', 'yade.minieigenHP'):
		mod = sys.modules.get(modName)
		if mod is not None:
			ns.update((k, v) for k, v in vars(mod).items() if not k.startswith('__'))
	ns.update(globals())
	return ns


def addAutoData():
	"""Append a row by evaluating the names in :data:`plots`.

	Each x key and y item may be an expression (its text is the column
	name), ``name=expression``, or a dict-like object whose items are added.
	Expressions are evaluated in this module's namespace plus the ``yade``
	package's; one that raises is skipped with a warning.
	"""
	ns = _evalNamespace()

	def evalInto(col, dic):
		name, expr = col.split('=', 1) if '=' in col else (col, col)
		try:
			dic[name] = eval(expr, ns)
		except Exception:
			print('WARN: ignoring exception raised while evaluating auto-column `' + expr + "'%s." % ('' if name == expr else ' (' + name + ')'))

	row = {}
	for p in plots:
		evalInto(p.strip(), row)
		for y in tuplifyYAxis(plots[p]):
			if y is None:
				continue
			yy = addPointTypeSpecifier(y, noSplit=True)[0]
			if hasattr(yy, 'keys'):
				row.update(dict(yy))
			else:
				evalInto(yy, row)
	addData(row)


# ---------------------------------------------------------------- matplotlib

_mplConfigured = False


def _hasDisplay():
	return bool(os.environ.get('DISPLAY') or os.environ.get('WAYLAND_DISPLAY'))


def _matplotlib():
	global _mplConfigured
	try:
		import matplotlib
	except ImportError:
		raise ImportError('yade.plot needs matplotlib for plotting; install it with: pip install matplotlib') from None
	if not _mplConfigured:
		if not _hasDisplay():
			backend = matplotlib.rcParams.get('backend', '')
			if 'matplotlib.pyplot' not in sys.modules or not isinstance(backend, str) or backend.lower() not in ('agg', 'pdf', 'ps', 'svg', 'pgf', 'cairo', 'template'):
				try:
					matplotlib.use('Agg', force=True)
				except Exception:
					pass
		matplotlib.rc('axes', grid=True)
		_mplConfigured = True
	return matplotlib


def _pyplot():
	_matplotlib()
	import matplotlib.pyplot as plt
	return plt


def __getattr__(name):
	# YADE's module has these as attributes; provide them lazily.
	if name == 'matplotlib':
		return _matplotlib()
	if name == 'pylab':
		_matplotlib()
		import pylab
		return pylab
	raise AttributeError("module 'yade.plot' has no attribute %r" % name)


def _omega():
	import builtins
	for holder in (sys.modules.get('yade'), builtins, sys.modules.get('__main__')):
		O = getattr(holder, 'O', None) if holder is not None else None
		if O is not None:
			return O
	return None


class LineRef(object):
	"A plotted line with the data columns it shows; :meth:`update` re-reads the columns."

	def __init__(self, line, scatter, line2, xdata, ydata, dataName=None):
		self.line, self.scatter, self.line2, self.xdata, self.ydata, self.dataName = line, scatter, line2, xdata, ydata, dataName

	def figure(self):
		return self.line.axes.get_figure()

	def update(self):
		if self.ydata is None:  # image plot
			col = imgData.get(self.dataName, []) if self.dataName else self.xdata
			try:
				self.line.set_data(_loadImage(col[current]))
			except IndexError:
				pass
			return
		if current is None or current == -1 or afterCurrentAlpha == 1:
			self.line.set_data(self.xdata, self.ydata)
			self.line2.set_data([], [])
		else:
			end = current + (1 if len(self.xdata) > current else 0)
			self.line.set_data(self.xdata[:end], self.ydata[:end])
			self.line2.set_data(self.xdata[current:], self.ydata[current:])
		if self.scatter is not None:
			try:
				self.scatter.set_offsets([[float(self.xdata[current]), float(self.ydata[current])]])
			except (IndexError, TypeError, ValueError):
				pass


def _loadImage(fileName):
	if fileName is None:
		import numpy
		return numpy.zeros((1, 1, 4))
	import matplotlib.image
	return matplotlib.image.imread(fileName)


def _finite0(v):
	try:
		return 0 if math.isnan(v) else v
	except TypeError:
		return v


def _createLines(ax, p, pStrip, ySpecs, isY1, y2Exists, scatterSize):
	expanded = []
	for ys in ySpecs:
		if callable(ys[0]):
			expanded += [(name, ys[1]) for name in ys[0]()]
		elif hasattr(ys[0], 'keys'):
			expanded += [(name, '') for name in list(ys[0].keys())]
		else:
			expanded.append(ys)
	if not expanded:
		print('yade.plot: creating fake plot, since there are no y-data yet')
		line, = ax.plot([nan], [nan])
		line2, = ax.plot([nan], [nan])
		currLineRefs.append(LineRef(line, None, line2, [nan], [nan]))
	# Like YADE, switch the global colour cycle here; the axes already exist, so
	# this colours the axes created next (the right axis, the next subplot).
	import matplotlib
	matplotlib.rcParams['axes.prop_cycle'] = matplotlib.cycler(color=(['m', 'y', 'k', 'b', 'g', 'r', 'c'] if isY1 else ['b', 'g', 'r', 'c', 'm', 'y', 'k']))
	xs = data[pStrip]
	for spec in expanded:
		name, fmt = spec[0], (spec[1] if len(spec) > 1 else '')
		if name not in data:  # a callable/dict named a column that does not exist yet
			print('yade.plot: creating new line for', name)
			data[name] = [nan] * len(xs)
		ys = data[name]
		line, = ax.plot(xs, ys, fmt, label=xlateLabel(name))
		with warnings.catch_warnings():  # fmt may name a colour too; the explicit one wins, as intended
			warnings.simplefilter('ignore', UserWarning)
			line2, = ax.plot([], [], fmt, color=line.get_color(), alpha=afterCurrentAlpha)
		scatter = None
		if isinstance(current, int):
			try:
				pt = (0, 0) if len(xs) == 0 else (_finite0(xs[current]), _finite0(ys[current]))
				scatter = ax.scatter(pt[0], pt[1], s=scatterSize, color=line.get_color(), **scatterMarkerKw)
			except IndexError:
				scatter = None
		currLineRefs.append(LineRef(line, scatter, line2, xs, ys))
	with warnings.catch_warnings():  # 'no artists with labels' for an empty fake plot
		warnings.simplefilter('ignore', UserWarning)
		ax.legend(loc=(legendLoc[0 if isY1 else 1] if y2Exists else 'best'))
	if scientific:
		try:
			ax.ticklabel_format(style='sci', scilimits=(0, 0), axis='both')
		except (AttributeError, ValueError):
			pass  # non-scalar formatter (log/category axes)
		if not isY1:
			ax.yaxis.set_offset_position('right')
	auto = ', '.join(xlateLabel(s[0]) for s in expanded)
	given = xylabels.get(p) if p in xylabels else None
	if isY1:
		ax.set_ylabel(given[1] if given and len(given) > 1 and given[1] else auto)
		ax.set_xlabel(given[0] if given and given[0] else xlateLabel(pStrip))
	else:
		ax.set_ylabel(given[2] if given and len(given) > 2 and given[2] else auto)


def createPlots(subPlots=True, scatterSize=60, wider=False):
	"Create matplotlib figures for :data:`plots` (closing the ones made by the previous call)."
	global currLineRefs
	plt = _pyplot()
	old = []
	for ref in currLineRefs:
		f = ref.figure()
		if f not in old:
			old.append(f)
	for f in old:
		plt.close(f)
	currLineRefs = []
	if len(plots) == 0:
		return
	if subPlots:
		subCols = int(round(math.sqrt(len(plots))))
		subRows = int(math.ceil(len(plots) * 1. / subCols))
		if wider:
			subRows, subCols = subCols, subRows
	for nPlot, p in enumerate(list(plots.keys())):
		pStrip = p.strip().split('=', 1)[0]
		if subPlots:
			ax = plt.subplot(subRows, subCols, nPlot + 1)
		else:
			ax = plt.figure().add_subplot(1, 1, 1)
		if plots[p] is None:  # image plot
			col = imgData.setdefault(pStrip, [])
			img = ax.imshow(_loadImage(col[-1] if col else None), origin='lower')
			currLineRefs.append(LineRef(img, None, None, col, None, pStrip))
			ax.set_axis_off()
			continue
		specs = [addPointTypeSpecifier(o) for o in tuplifyYAxis(plots[p])]
		y1, y2 = [], []
		onY1 = True
		missing = []
		if pStrip not in data:
			missing.append(pStrip)
		for spec in specs:
			if spec[0] is None:
				onY1 = False
				continue
			(y1 if onY1 else y2).append(spec)
			if not callable(spec[0]) and not hasattr(spec[0], 'keys') and spec[0] not in data and spec[0] not in missing:
				missing.append(spec[0])
		if missing:
			if _numRows() == 0:  # nothing recorded yet: empty columns, no NaN rows
				for m in missing:
					data[m] = []
			else:
				print('Missing columns in plot.data, adding NaN: ', ','.join(missing))
				addDataColumns(missing)
		_createLines(ax, p, pStrip, y1, True, len(y2) > 0, scatterSize)
		if axesWd > 0:
			ax.axhline(linewidth=axesWd, color='k')
			ax.axvline(linewidth=axesWd, color='k')
		last = ax
		if y2:
			last = ax.twinx()
			_createLines(last, p, pStrip, y2, False, True, scatterSize)
		try:
			O = _omega()
			if O is not None and 'title' in list(O.tags.keys()):
				last.set_title(O.tags['title'])
		except Exception:
			pass


def _figures():
	figs = []
	for ref in currLineRefs:
		f = ref.figure()
		if f not in figs:
			figs.append(f)
	return figs


def _scriptStem():
	candidates = [sys.argv[0] if sys.argv else '', getattr(sys.modules.get('__main__'), '__file__', None) or '']
	for c in candidates:
		if c and c.endswith('.py'):
			return os.path.splitext(os.path.basename(c))[0]
	return 'yade'


def plotFileName():
	"Where :func:`plot` saves the figure: ``$RYADE_PLOT_FILE`` or ``<script stem>.plot.png`` in the working directory."
	env = os.environ.get('RYADE_PLOT_FILE')
	if env:
		return env
	return os.path.join(os.getcwd(), _scriptStem() + '.plot.png')


def _saveFigures(figs, path, how):
	root, ext = os.path.splitext(path)
	for i, fig in enumerate(figs):
		out = path if i == 0 else '%s.%d%s' % (root, i, ext)
		# the figure is not handed to the user: enlarge it to fit its grid of subplots
		rows, cols = 1, 1
		for ax in fig.axes:
			spec = ax.get_subplotspec() if hasattr(ax, 'get_subplotspec') else None
			if spec is not None:
				rows, cols = spec.get_gridspec().get_geometry()
				break
		w, h = fig.get_size_inches()
		fig.set_size_inches(max(w, 6.4 * cols), max(h, 4.8 * rows))
		try:
			with warnings.catch_warnings():
				warnings.simplefilter('ignore')
				fig.tight_layout()
		except Exception:
			pass
		d = os.path.dirname(out)
		if d and not os.path.isdir(d):
			os.makedirs(d, exist_ok=True)
		fig.savefig(out)
		print('yade.plot: figure %s %s' % (how, out))


# what the last plot(noShow=False) saved, to refresh the file at exit (YADE's
# window would keep updating while the simulation goes on)
_lastSave = None
_atexitRegistered = False


def _dataSignature():
	return (id(data), _numRows(), tuple(data.keys()))


def _refreshAtExit():
	global _lastSave
	if _lastSave is None:
		return
	subPlots, path, signature = _lastSave
	_lastSave = None
	if signature == _dataSignature():
		return
	try:
		createPlots(subPlots=subPlots)
		figs = _figures()
		if figs:
			_saveFigures(figs, path, 'updated with the final data in')
	except Exception as e:
		print('yade.plot: could not update %s at exit: %s' % (path, e))


def plot(noShow=False, subPlots=True):
	"""Draw :data:`plots`.

	``noShow=True``: return the matplotlib Figure (a list of them if there are
	several, e.g. with ``subPlots=False``).  ``noShow=False``: ryade is
	headless, so the figure is saved as PNG (see :func:`plotFileName`; further
	figures get ``.1``, ``.2`` ... before the extension), the path is printed
	and None is returned.  Since YADE would go on updating the window live,
	the file is drawn again at interpreter exit if :data:`data` changed.
	"""
	global _lastSave, _atexitRegistered
	createPlots(subPlots=subPlots)
	figs = _figures()
	if not figs:
		raise IndexError('yade.plot.plot(): plot.plots is empty, there is nothing to plot')
	if noShow:
		return figs[0] if len(figs) == 1 else figs
	path = os.path.abspath(plotFileName())
	_saveFigures(figs, path, 'saved to')
	_lastSave = (subPlots, path, _dataSignature())
	if not _atexitRegistered:
		import atexit
		atexit.register(_refreshAtExit)
		_atexitRegistered = True
	return None


def liveUpdate(timestamp):
	raise NotImplementedError(_NOT_SUPPORTED % 'liveUpdate')


def savePlotSequence(fileBase, stride=1, imgRatio=(5, 7), title=None, titleFrames=20, lastFrames=30):
	raise NotImplementedError(_NOT_SUPPORTED % 'savePlotSequence')


def createTitleFrame(out, size, title):
	raise NotImplementedError(_NOT_SUPPORTED % 'createTitleFrame')


def savePylab(baseName, timestamp=False, title=None):
	raise NotImplementedError(_NOT_SUPPORTED % 'savePylab')


# ---------------------------------------------------------------- text export


def saveDataTxt(fileName, vars=None, headers=None):
	"""Write :data:`data` as a tab-separated text file, compressed if *fileName* ends in ``.bz2`` or ``.gz``.

	Optional ``# key=<TAB>value`` lines from *headers* come first, then
	``# `` and the column names joined by two tabs, then one line per row
	with ``str()`` of each value joined by one tab.  *vars* selects and
	orders the columns (default: all, sorted by name).
	"""
	import bz2
	import gzip
	if not vars:
		vars = sorted(data.keys())
	else:
		vars = list(vars)
	if fileName.endswith('.bz2'):
		f, binary = bz2.BZ2File(fileName, 'w'), True
	elif fileName.endswith('.gz'):
		f, binary = gzip.GzipFile(fileName, 'w'), True
	else:
		f, binary = open(fileName, 'w'), False

	def put(text):
		f.write(text.encode('utf-8') if binary else text)

	try:
		if headers:
			for k in list(headers.keys()):
				put('# %s=\t%s\n' % (k, headers[k]))
		put('# ' + '\t\t'.join(vars) + '\n')
		for i in range(len(data[vars[0]])):
			put('\t'.join(str(data[v][i]) for v in vars) + '\n')
	finally:
		f.close()


def _mkTimestamp():
	return time.strftime('_%Y%m%d_%H:%M')


def saveGnuplot(baseName, term='wxt', extension=None, timestamp=False, comment=None, title=None, varData=False):
	"""Write ``baseName.data.bz2`` (all columns, see :func:`saveDataTxt`) and ``baseName.gnuplot`` with one plot per entry of :data:`plots`; return the .gnuplot file name.

	*term*: gnuplot terminal (``wxt``/``x11`` open persistent windows, others
	write ``baseName.<n>.<extension>``, *extension* defaulting to *term*);
	*timestamp*: append ``_YYYYmmdd_HH:MM`` to *baseName*; *comment*: text
	put in the file as comment lines; *title*: plot title; *varData*: refer to
	the data through a gnuplot variable.
	"""
	if len(data) == 0:
		raise RuntimeError("No data for plotting were saved.")
	if timestamp:
		baseName += _mkTimestamp()
	baseNameNoPath = baseName.split('/')[-1]
	vars = sorted(data.keys())
	saveDataTxt(fileName=baseName + '.data.bz2', vars=vars)
	fPlot = open(baseName + '.gnuplot', 'w')
	try:
		fPlot.write('#!/usr/bin/env gnuplot\n#\n# created ' + time.asctime() + ' (' + time.strftime('%Y%m%d_%H:%M') + ')\n#\n')
		if comment:
			fPlot.write('# ' + comment.replace('\n', '\n# ') + '#\n')
		dataFile = '"< bzcat %s.data.bz2"' % baseNameNoPath
		if varData:
			fPlot.write('dataFile=%s' % dataFile)  # YADE writes no newline here
			dataFile = 'dataFile'
		if not extension:
			extension = term
		nPlot = 0
		for p in plots:
			pStrip = p.strip().split('=', 1)[0]
			if plots[p] is None:
				continue  # image plots have no gnuplot counterpart
			specs = [addPointTypeSpecifier(o) for o in tuplifyYAxis(plots[p])]
			if term in ('wxt', 'x11'):
				fPlot.write('set term %s %d persist\n' % (term, nPlot))
			else:
				fPlot.write("set term %s; set output '%s.%d.%s'\n" % (term, baseNameNoPath, nPlot, extension))
			fPlot.write("set xlabel '%s'\n" % xlateLabel(p))
			fPlot.write('set grid\n')
			fPlot.write("set datafile missing 'nan'\n")
			if title:
				fPlot.write("set title '%s'\n" % title)
			expanded = []
			for spec in specs:
				if callable(spec[0]):
					expanded += [(name, '') for name in spec[0]() if name in data]
				elif hasattr(spec[0], 'keys'):
					expanded += [(name, val) for name, val in list(spec[0].items()) if name in data]
				else:
					expanded.append((spec[0], spec[1]))
			y1, y2 = [], []
			onY1 = True
			for spec in expanded:
				if spec[0] is None:
					onY1 = False
					continue
				(y1 if onY1 else y2).append(spec)
			fPlot.write("set ylabel '%s'\n" % ','.join(xlateLabel(s[0]) for s in y1))
			if y2:
				fPlot.write("set y2label '%s'\n" % ','.join(xlateLabel(s[0]) for s in y2))
				fPlot.write('set y2tics\n')
			parts = []
			for spec in y1:
				parts.append(" %s using %d:%d title '← %s(%s)' with lines" % (dataFile, vars.index(pStrip) + 1, vars.index(spec[0]) + 1, xlateLabel(spec[0]), xlateLabel(pStrip)))
			for spec in y2:
				parts.append(" %s using %d:%d title '%s(%s) →' with lines axes x1y2" % (dataFile, vars.index(pStrip) + 1, vars.index(spec[0]) + 1, xlateLabel(spec[0]), xlateLabel(pStrip)))
			fPlot.write('plot ' + ','.join(parts) + '\n')
			nPlot += 1
	finally:
		fPlot.close()
	return baseName + '.gnuplot'
