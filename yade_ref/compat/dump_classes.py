# Dump every YADE class (Serializable descendants), its base class and its attribute names, so that
# ryade's compat layer can tell "exists in YADE but not implemented in ryade" from "no such thing".
# Run: yade -n -x yade_ref/compat/dump_classes.py OUT.json
import sys, json
import yade.system
out = {}
names = sorted(yade.system.childClasses('Serializable')) + ['Serializable']
for n in names:
    try:
        cls = eval(n)
    except Exception:
        continue
    attrs = []
    try:
        obj = cls()
        attrs = sorted(obj.dict().keys())
    except Exception:
        pass
    methods = sorted(a for a in dir(cls) if not a.startswith('_') and callable(getattr(cls, a, None)))
    bases = [b.__name__ for b in cls.__mro__[1:] if b.__name__ not in ('object', 'instance', 'Boost.Python.instance')]
    out[n] = {'bases': bases, 'attrs': attrs, 'methods': methods}
json.dump(out, open(sys.argv[1], 'w'), indent=0, sort_keys=True)
print('classes:', len(out))
sys.stdout.flush()
