"""`yade.qt` headless: YADE scripts open views for people; ryade runs without a display, so these are
harmless stand-ins (the only place where the compat layer deliberately does nothing)."""


class _NoGui(object):
    def __init__(self, *a, **kw):
        pass

    def __getattr__(self, k):
        if k.startswith('__'):
            raise AttributeError(k)
        return _NoGui()

    def __call__(self, *a, **kw):
        return _NoGui()

    def __setattr__(self, k, v):
        object.__setattr__(self, k, v)


def View(*a, **kw):
    return _NoGui()


def Controller(*a, **kw):
    return _NoGui()


def Renderer(*a, **kw):
    return _NoGui()


def views():
    return []


def close():
    pass


def __getattr__(name):
    if name.startswith('__'):
        raise AttributeError(name)
    return _NoGui()
