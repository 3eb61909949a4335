# the module changes nothing process-wide in the interpreter that imports it: it defines no global
# operator new or delete (the gransim executable's huge-page allocator stays in the executable)
import shutil
import subprocess

import pytest

import gransim

GLOBAL_ALLOCATION = {"_Znwm", "_Znam", "_ZnwmRKSt9nothrow_t", "_ZnamRKSt9nothrow_t", "_ZdlPv",
                     "_ZdaPv", "_ZdlPvm", "_ZdaPvm", "_ZdlPvRKSt9nothrow_t", "_ZdaPvRKSt9nothrow_t"}


def defined_symbols(path):
    out = subprocess.run(["nm", "-D", "--defined-only", path], check=True, capture_output=True,
                         text=True).stdout
    return {line.split()[-1] for line in out.splitlines() if line.strip()}


@pytest.mark.skipif(shutil.which("nm") is None, reason="binutils' nm is not installed")
def test_module_defines_no_global_allocator():
    syms = defined_symbols(gransim._gransim.__file__)
    assert syms, "nm found no dynamic symbols at all: the check would prove nothing"
    assert "PyInit__gransim" in syms
    assert not (syms & GLOBAL_ALLOCATION), sorted(syms & GLOBAL_ALLOCATION)

