"""delvjax's tests, laid out as the package is (tests/core, tests/sweeps, ...).

`typecheck` checks the package's type hints and jaxtyping shapes at run time in the whole suite
(pyproject.toml: jaxtyping's pytest hook, `--jaxtyping-packages=delvjax,tests.typecheck`): beartype,
with PEP 484's numeric tower (an int passes where a float is hinted, as Python's own typing says).
"""

from contextlib import contextmanager

try:
    from beartype import BeartypeConf, beartype
except ImportError:  # a benchmark borrowing the NumPy twins on a machine without the test extra (a GPU image)

    def typecheck(f):
        return f

else:
    typecheck = beartype(conf=BeartypeConf(is_pep484_tower=True))


@contextmanager
def hints_unchecked():
    """For a test that passes a value of the wrong type on purpose to see delvjax's own one-line
    error (naming the field): the run-time checks of the hints step aside while it runs."""
    import jaxtyping

    jaxtyping.config.update("jaxtyping_disable", True)
    try:
        yield
    finally:
        jaxtyping.config.update("jaxtyping_disable", False)
