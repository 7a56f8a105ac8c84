"""Stand-in for python3-future's `future` (see ../README.md)."""
