# Dump the names a YADE script can reach outside the class tables (yade_ref/compat/dump_classes.py):
# the `yade -x` startup namespace, every public name of YADE's Python modules, and the attributes of
# O and its containers. `compat run --check` (compat/python/yade/_check.py) finds a script's
# unsupported names against these tables. Run: yade -n -x yade_ref/compat/dump_names.py OUT.json
import sys, json, importlib, pkgutil
import yade, yade.system

# class names are in the class table; the modules re-export them
classes = set(yade.system.childClasses('Serializable')) | {'Serializable'}

ns = sorted(k for k in globals() if not k.startswith('_') and k not in classes)
modules = {}
for m in sorted(set(n for _, n, _ in pkgutil.iter_modules(yade.__path__)) | {'utils', 'pack', 'export', 'ymport', 'plot', 'geom',
                                                                           'timing', 'qt', 'gridpfacet', 'params', 'post2d', 'linterpolation',
                                                                           'polyhedra_utils', 'bodiesHandling', 'remote', 'system', 'wrapper',
                                                                           'log', 'math', 'minieigenHP'}):
    if m.startswith('_'):
        continue
    try:
        mod = importlib.import_module('yade.' + m)
    except BaseException as e:
        modules[m] = {'error': type(e).__name__}
        continue
    modules[m] = {'names': sorted(k for k in dir(mod) if not k.startswith('_') and k not in classes)}
objs = {'O': O, 'O.bodies': O.bodies, 'O.interactions': O.interactions, 'O.forces': O.forces, 'O.materials': O.materials,
        'O.cell': O.cell, 'O.energy': O.energy, 'O.tags': O.tags}
attrs = {k: sorted(a for a in dir(v) if not a.startswith('_')) for k, v in objs.items()}
json.dump({'namespace': ns, 'modules': modules, 'objects': attrs}, open(sys.argv[1], 'w'), indent=0, sort_keys=True)
print('namespace %d names, %d modules' % (len(ns), len(modules)))
sys.stdout.flush()
