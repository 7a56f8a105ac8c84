"""Stand-in for python3-future's `past` (see ../README.md)."""
