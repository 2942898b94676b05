"""Import dolfinx without putting its libraries in the process's global symbols.

Debian's dolfinx 0.5.2 ``__init__`` sets ``sys.setdlopenflags(RTLD_NOW |
RTLD_GLOBAL)`` and never restores it.  Its libraries (libdolfinx_real,
Trilinos) then export their std::regex template instances to every library
loaded later, and VTK's PyPI wheel (built with the old C++ string ABI) binds
to them: its first scalar bar aborts the process with std::bad_alloc
(seen with `LD_DEBUG=bindings`).  Loading dolfinx with the default flags
keeps each library's templates its own; dolfinx, its JIT-compiled forms and
PETSc work unchanged (the whole test suite runs so).
"""

from __future__ import annotations

import sys


def import_dolfinx():
    """The dolfinx module, imported with the caller's dlopen flags kept."""
    if "dolfinx" in sys.modules:
        return sys.modules["dolfinx"]
    real = sys.setdlopenflags
    sys.setdlopenflags = lambda flags: None
    try:
        import dolfinx
    finally:
        sys.setdlopenflags = real
    return dolfinx
