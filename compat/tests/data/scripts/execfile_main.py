# YADE's `execfile` (its startup imports it from past.builtins): the file runs in this script's
# namespace (it sees `r` and YADE's names, and what it defines is seen here), or in a given dict.
import os, sys
here = os.path.dirname(os.path.abspath(sys.argv[0]))
r = 0.25
execfile(os.path.join(here, 'execfile_part.py'))
print('A %d %r %r' % (len(O.bodies), O.bodies[1].state.pos[2], volume))
g = {'k': 3}
execfile(os.path.join(here, 'execfile_dict.py'), g)
print('B %r %r' % (g['q'], 'q' in globals()))
