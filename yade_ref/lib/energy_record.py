"""O.energy recorded every few steps, for the golden/energy scenes (yade_ref/energy/*.py): one row per
record, `iteration,O.energy.total(),name=value,...` (O.energy.items()), every value as repr()."""
import os
import sys


def out_dir():
    """The scripts' output folder: argv[1], else golden/energy of this checkout."""
    here = os.path.dirname(os.path.abspath(sys.argv[0]))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, '..', '..', 'golden', 'energy')
    os.makedirs(out, exist_ok=True)
    return out


def record(O, path, steps, every=1):
    O.trackEnergy = True
    rows = []
    for _ in range(steps // every):
        O.run(every, True)
        rows.append('%d,%r,%s' % (O.iter, O.energy.total(), ','.join('%s=%r' % kv for kv in O.energy.items())))
    with open(path, 'w') as f:
        f.write('\n'.join(rows) + '\n')
    print('%s: %d rows, keys %s' % (os.path.basename(path), len(rows), O.energy.keys()))
    sys.stdout.flush()
