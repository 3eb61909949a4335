"""`pip install .`: setuptools drives CMake to build gransim._gransim for the interpreter that
runs pip, then installs it with the pure-Python package (pyproject.toml holds the metadata).

Environment: GS_PIP_BUILD_DIR (setuptools' and CMake's build folders; default build/pip in the
source tree, kept so a second install rebuilds only what changed), GS_CMAKE_BUILD_DIR (CMake's
folder alone; default GS_PIP_BUILD_DIR/cmake), GS_CMAKE_ARGS (more -D options), GS_JOBS
(parallel compile jobs).
"""

import os
import re
import shlex
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
# setuptools' build/ and egg-info and CMake's tree in one folder, out of the sources
BUILD_BASE = Path(os.environ.get("GS_PIP_BUILD_DIR") or ROOT / "build" / "pip").resolve()


def project_version():
    """the version CMakeLists.txt declares, so the wheel and `gransim --version` agree"""
    text = (ROOT / "CMakeLists.txt").read_text()
    found = re.search(r"project\(gransim VERSION ([0-9][0-9.]*)", text)
    if not found:
        sys.exit("setup.py: no 'project(gransim VERSION x.y.z' in CMakeLists.txt")
    return found.group(1)


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        if shutil.which("cmake") is None:
            sys.exit("setup.py: cmake is not on PATH (Debian: apt-get install cmake; tools/setup.sh "
                     "installs every build dependency)")
        build_dir = Path(os.environ.get("GS_CMAKE_BUILD_DIR") or BUILD_BASE / "cmake").resolve()
        args = [
            f"-DPython_EXECUTABLE={sys.executable}",
            "-DCMAKE_BUILD_TYPE=Release",
            "-DGS_WITH_PYTHON=ON",
            "-DGS_BUILD_TESTS=OFF",
            "-DGS_BUILD_BENCH=OFF",
        ]
        try:
            import pybind11
            # searched after the system's config (CMakeLists.txt), so that both builds agree
            args.append(f"-DGS_PYBIND11_HINT={pybind11.get_cmake_dir()}")
        except ImportError:
            pass  # CMake looks for pybind11's config in its usual places
        if shutil.which("ccache") and "CMAKE_CXX_COMPILER_LAUNCHER" not in os.environ:
            args.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
        args += shlex.split(os.environ.get("GS_CMAKE_ARGS", ""))
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build_dir), *args], check=True)
        jobs = os.environ.get("GS_JOBS") or str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "gransim_python",
                        "-j", jobs], check=True)

        # the module CMake built for this interpreter (its name carries the ABI tag)
        suffix = sysconfig.get_config_var("EXT_SUFFIX")
        built = build_dir / "python" / "gransim" / f"_gransim{suffix}"
        if not built.exists():
            sys.exit(f"setup.py: CMake did not build {built}: was pybind11 found for "
                     f"{sys.executable}? (Debian: python3-pybind11 python3-dev)")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


BUILD_BASE.mkdir(parents=True, exist_ok=True)
setup(
    version=project_version(),
    options={"build": {"build_base": str(BUILD_BASE)}, "egg_info": {"egg_base": str(BUILD_BASE)}},
    ext_modules=[CMakeExtension("gransim._gransim")],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)
