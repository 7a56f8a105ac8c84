# One run of the gap-diagnosis sweeps, driven by a yade-batch parameter table (`compat batch` or
# `yade-batch`; see yade_ref/gap/README.md). It turns the table line into study.py arguments and runs
# yade_ref/study/study.py in this interpreter, so the same table runs in ryade, in Debian YADE, or as a
# Slurm job array (`compat batch TABLE yade_ref/gap/run_case.py --emit-slurm job.sh`).
#
# Columns (all optional except out):
#   ratio case size seed cycles : the study case (see yade_ref/study/README.md)
#   specimen                    : load this specimen instead of generating ('' = generate)
#   export                      : when generating, also write the specimen there (--export-specimen)
#   generate_only               : 1 = stop after generation (and the export), no loading
#   effects                     : comma-separated knob=value pairs, e.g. 'eta_roll=0.3,subgrade_k=2e7'
#                                 (knob names = study.py options with '-' written '_', without '--')
#   controller                  : study.py's --controller (ryade's fast library runs: 'native', the
#                                 piston law in Rust, byte-identical to the PyRunner; '' = the PyRunner)
#   out                         : output directory
import os, sys

from yade import utils

utils.readParamsFromTable(ratio=0.7, case='G', size='tiny', seed=1, cycles=5, specimen='', export='', generate_only=0, effects='', controller='', out='gap_out/run',
                          noTableOk=True)
from yade.params import table as T

argv = ['--out', T.out, '--cycles', str(int(T.cycles))]
if T.specimen:
    argv += ['--import-specimen', T.specimen]
else:
    argv += ['--ratio', str(T.ratio), '--case', T.case, '--size', T.size, '--seed', str(int(T.seed))]
    if T.export:
        argv += ['--export-specimen', T.export]
    if int(T.generate_only):
        argv += ['--generate-only']
if T.controller:
    argv += ['--controller', T.controller]
for pair in [p for p in T.effects.split(',') if p]:
    k, v = pair.split('=', 1)
    argv += ['--' + k.strip().replace('_', '-'), v.strip()]
here = os.path.dirname(os.path.abspath(sys.argv[0]))  # YADE's -x sets argv[0], not __file__
study = os.path.join(here, '..', 'study', 'study.py')
sys.argv = [study] + argv
print('[gap] study.py ' + ' '.join(argv), flush=True)
exec(compile(open(study).read(), study, 'exec'), globals())
