"""Builds the extension proxima._proxima with the project's CMake (PROXIMA_BUILD_PYTHON) for
`pip install --no-build-isolation .`; pyproject.toml holds the package's metadata.

Steps: configure a release build in the build_ext temporary folder (tests, benchmarks and
examples off; the tool on, since proxima.render uses its renderer) for the interpreter
running pip, build the target proxima_python, copy the module where setuptools packs it."""

import os
import pathlib
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext


class CMakeExtension(Extension):
    """An extension CMake builds (no sources of its own for setuptools)."""

    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        root = pathlib.Path(__file__).parent.resolve()
        build = pathlib.Path(self.build_temp).resolve() / "cmake"
        configure = [
            "cmake", "-S", str(root), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
            "-DPROXIMA_BUILD_PYTHON=ON", "-DPROXIMA_BUILD_TESTS=OFF", "-DPROXIMA_BUILD_BENCH=OFF",
            "-DPROXIMA_BUILD_EXAMPLES=OFF", f"-DPython3_EXECUTABLE={sys.executable}",
        ]
        if shutil.which("ccache"):
            configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
        subprocess.run(configure, check=True)
        jobs = str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", str(build), "--target", "proxima_python", "-j", jobs], check=True)
        built = next((build / "python" / "proxima").glob("_proxima*.so"))
        target = pathlib.Path(self.get_ext_fullpath(ext.name)).resolve()
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built, target)


setup(ext_modules=[CMakeExtension("proxima._proxima")], cmdclass={"build_ext": CMakeBuild})
