"""`yade.minieigenHP`: YADE 2023's name for its minieigen module."""
from .minieigen import *  # noqa: F401,F403
