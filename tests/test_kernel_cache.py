"""numba's cache of the reduced model's kernels is keyed by their sources' contents.

numba's own staleness stamp is a kernel file's time and size: a kernel of fixed_step.py that
inlines rhs.py's functions kept its compiled code after rhs.py changed, and a fixed-step run-up
then stayed at 0 rad/s (found by the full suite on a working tree that had compiled it before
the change; a fresh clone never sees it)."""

from pathlib import Path

import numba

from rotorpillar.reduced import rhs


def test_a_change_in_any_kernel_source_moves_the_cache(tmp_path):
    files = []
    for name, text in (("rhs.py", "a = 1\n"), ("dp5.py", "b = 2\n")):
        p = tmp_path / name
        p.write_text(text)
        files.append(p)
    root = tmp_path / "cache"
    before = rhs.kernel_cache_dir(tuple(files), root)
    assert rhs.kernel_cache_dir(tuple(files), root) == before  # the same sources: the same cache
    files[0].write_text("a = 2\n")  # rhs.py changes, dp5.py does not
    assert rhs.kernel_cache_dir(tuple(files), root) != before


def test_the_kernels_compile_into_the_keyed_cache():
    here = Path(rhs.__file__).resolve().parent
    expected = rhs.kernel_cache_dir(tuple(here / f for f in rhs.KERNEL_SOURCES), Path("x")).name
    # the user's NUMBA_CACHE_DIR wins; otherwise the keyed directory
    assert Path(numba.config.CACHE_DIR).name == expected or "NUMBA_CACHE_DIR" in __import__("os").environ
