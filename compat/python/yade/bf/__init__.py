"""`yade.bf` (YADE's py/bf): the clump breakage functions of Brzezinski & Gladkyy (2022). YADE's
startup puts the yade package folder on sys.path, so scripts import it as `bf` too."""
from .bf import checkFailure, evalClump, replaceSphere, stressTensor  # noqa: F401
