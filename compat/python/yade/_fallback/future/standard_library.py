"""Stand-in for `future.standard_library`: on Python 3 the standard library already has the Python 3
names, so installing the aliases does nothing."""


def install_aliases():
    pass
